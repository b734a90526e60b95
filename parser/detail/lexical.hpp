#pragma once
// Plain lexical pieces of CL, with no X3 in them: shared by the grammar's primitives
// (number_parser.hpp, text_major_parser.hpp) and the fast path for numeric records
// (fast_record.cpp), so that both read characters, numbers and text majors alike.
#include <cstddef>
#include <string_view>

#include "support/ascii.hpp"

namespace twinpost::parser_detail {

// Letters, digits and '_' (ASCII only), one table look-up: it is asked after every number.
inline constexpr auto word_chars = [] {
  struct table {
    bool in[256] = {};
  } t;
  for (int c = 0; c < 256; ++c) t.in[c] = ascii::is_alnum(static_cast<char>(c)) || c == '_';
  return t;
}();

inline bool is_word_char(char c) { return word_chars.in[static_cast<unsigned char>(c)]; }

// The common CL number (`123.4567`, at most 15 digits, no exponent) without from_chars:
// the digits as an exact integer divided by an exact power of ten is one correctly rounded
// IEEE division (Clinger's fast path), so the value equals from_chars'. Returns the end of
// the number, or nullptr to hand the text to from_chars (exponents, long numbers, "." alone).
inline const char* fast_decimal(const char* p, const char* last, double& value) {
  static constexpr double pow10[] = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                     1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
  // Digits first, counted afterwards: more than 15 go to from_chars, so the unsigned
  // arithmetic here may wrap on a long number without harm.
  unsigned long long mantissa = 0;
  const char* int_begin = p;
  while (p != last && static_cast<unsigned>(*p - '0') < 10)
    mantissa = mantissa * 10 + static_cast<unsigned>(*p++ - '0');
  int digits = static_cast<int>(p - int_begin), fraction = 0;
  if (p != last && *p == '.') {
    const char* frac_begin = ++p;
    while (p != last && static_cast<unsigned>(*p - '0') < 10)
      mantissa = mantissa * 10 + static_cast<unsigned>(*p++ - '0');
    fraction = static_cast<int>(p - frac_begin);
    digits += fraction;
  }
  if (digits > 15) return nullptr;
  if (digits == 0) return nullptr;
  if (p != last && (*p == 'e' || *p == 'E')) return nullptr;
  value = static_cast<double>(mantissa) / pow10[fraction];
  return p;
}

/// The majors of free-text records (PARTNO, PPRINT, ...), matched case-insensitively.
inline constexpr std::string_view text_majors[] = {
    "PARTNO", "PPRINT", "INSERT", "TPRINT", "OPFEATSTART", "OPFEATEND", "TOOL PATH", "TITLES", "REMARK"};

/// The length of the text major that `s` starts with as a whole word, or 0.
inline std::size_t text_major_length(std::string_view s) {
  if (s.empty()) return 0;
  const char first = ascii::upper(s[0]);
  if (first != 'P' && first != 'I' && first != 'T' && first != 'O' && first != 'R') return 0;
  for (std::string_view w : text_majors) {
    if (w[0] != first) continue;
    if (!ascii::starts_with_keyword(s, w)) continue;
    if (s.size() > w.size() && is_word_char(s[w.size()])) continue;  // PARTNOX is a statement
    return w.size();
  }
  return 0;
}

}  // namespace twinpost::parser_detail
