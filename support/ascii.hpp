#pragma once
// ASCII character classes and case, locale-free. Input is ASCII by the project's rule: CL and
// NC words are ASCII, and ISO-8859-1 or UTF-8 bytes in comments are never letters. The C
// library's <cctype> consults the locale, is undefined for a negative char, and is a call
// per character: none of it is used. Everything here is inline and allocation-free, so
// per-record paths can use it (upper_copy allocates: keep it off those paths).
#include <string>
#include <string_view>

namespace twinpost::ascii {

/// 'A'..'Z'.
constexpr bool is_upper(char c) { return c >= 'A' && c <= 'Z'; }
/// 'a'..'z'.
constexpr bool is_lower(char c) { return c >= 'a' && c <= 'z'; }
/// An ASCII letter; a byte >= 0x80 never is.
constexpr bool is_letter(char c) { return is_upper(c) || is_lower(c); }
/// '0'..'9'.
constexpr bool is_digit(char c) { return c >= '0' && c <= '9'; }
/// A blank between NC or CL words: a space or a tab.
constexpr bool is_blank(char c) { return c == ' ' || c == '\t'; }
/// An ASCII letter or digit.
constexpr bool is_alnum(char c) { return is_letter(c) || is_digit(c); }

/// `c` upper-cased if it is an ASCII lower-case letter, else `c` unchanged.
constexpr char upper(char c) { return is_lower(c) ? static_cast<char>(c - 'a' + 'A') : c; }

/// Upper-cases `s` in place (ASCII letters only).
constexpr void upper_in_place(std::string& s) {
  for (char& c : s) c = upper(c);
}

/// A copy of `s` with its ASCII letters upper-cased.
inline std::string upper_copy(std::string_view s) {
  std::string out(s);
  upper_in_place(out);
  return out;
}

/// True when `a` and `b` are equal but for the case of ASCII letters.
constexpr bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (upper(a[i]) != upper(b[i])) return false;
  return true;
}

/// True when `word` upper-cased is `keyword`, which is upper-case already ("GOTO"): only the
/// input is upper-cased, the form for matching records against keywords on per-record paths.
constexpr bool equals_keyword(std::string_view word, std::string_view keyword) {
  if (word.size() != keyword.size()) return false;
  for (std::size_t i = 0; i < word.size(); ++i)
    if (upper(word[i]) != keyword[i]) return false;
  return true;
}

/// True when `s` begins with the upper-case `keyword`, ignoring the case of `s`.
constexpr bool starts_with_keyword(std::string_view s, std::string_view keyword) {
  return s.size() >= keyword.size() && equals_keyword(s.substr(0, keyword.size()), keyword);
}

}  // namespace twinpost::ascii
