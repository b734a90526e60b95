#include "nc/nc_words.hpp"

#include <array>
#include <charconv>
#include <cstdint>
#include <cstring>

#include "support/ascii.hpp"
#include "support/swar.hpp"

namespace twinpost {

namespace {

using ascii::is_blank;
using ascii::is_digit;
using ascii::is_letter;
using ascii::upper;

// The digits and the point of a number, from `s[at]` (after any sign) up to the first
// character that is neither; `end` is where they stop. Digits, a point, digits: each run in a
// loop of its own (no test per character of which part it is in); a second point leaves the
// word as written, not a number.
struct decimal_scan {
  std::uint64_t mantissa = 0;  // wraps harmlessly past 19 digits: those go to nc_number
  std::size_t digits = 0, end = 0;
  int decimals = -1;  // digits after the point; -1: no point
  bool clean = true;  // at most one point

  decimal_scan(std::string_view s, std::size_t at) {
    // Pointers and a local sum, each digit tested by one unsigned compare: the digit loops
    // are most of the split's time.
    const char* const first = s.data() + at;
    const char* const e = s.data() + s.size();
    const char* p = first;
    std::uint64_t m = 0;
    for (unsigned dg; p < e && (dg = static_cast<unsigned char>(*p) - 48u) <= 9; ++p) m = m * 10 + dg;
    digits = static_cast<std::size_t>(p - first);
    if (p < e && *p == '.') {
      const char* const f = ++p;
      for (unsigned dg; p < e && (dg = static_cast<unsigned char>(*p) - 48u) <= 9; ++p) m = m * 10 + dg;
      decimals = static_cast<int>(p - f);
      digits += static_cast<std::size_t>(p - f);
      for (; p < e && (is_digit(*p) || *p == '.'); ++p) clean = false;
    }
    mantissa = m;
    end = static_cast<std::size_t>(p - s.data());
  }

  // The number as std::from_chars reads `text` (the word's value, sign included: nc_number).
  // NC numbers are short: the digits are divided by an exact power of ten, which rounds
  // correctly as from_chars does (Clinger's fast path) while they fit in 15; longer ones go to
  // from_chars. `point`: written with a decimal point.
  bool value(bool negative, std::string_view text, double& out, bool& point) const {
    static constexpr double pow10[] = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                       1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
    if (!clean || digits == 0) return false;
    point = decimals >= 0;
    if (digits > 15) return nc_number(text, out);
    out = static_cast<double>(mantissa) / pow10[decimals < 0 ? 0 : decimals];
    if (negative) out = -out;
    return true;
  }
};

// The number of a word's value as std::from_chars reads it (nc_number), decoded once when the
// block is split. `point`: written with a decimal point.
bool decode_number(std::string_view s, double& out, bool& point) {
  std::size_t i = 0;
  bool negative = false;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) negative = s[i++] == '-';
  const decimal_scan n(s, i);
  return n.end == s.size() && n.value(negative, s, out, point);
}

/// Index just past the `[...]` group that opens at `i` (groups nest).
std::size_t skip_brackets(std::string_view s, std::size_t i) {
  int depth = 0;
  for (; i < s.size(); ++i) {
    if (s[i] == '[') ++depth;
    if (s[i] == ']' && --depth == 0) return i + 1;
  }
  return i;
}

}  // namespace

const std::vector<nc_word>& nc_block::split() const {
  letters_ = split_nc_words(text, *store_);
  split_ = has_letters_ = true;
  return *store_;
}

std::uint32_t nc_block::scan_gms() const {
  // Byte flags ORed over the text: one compare per letter and case, vector code.
  unsigned char g = 0, m = 0, s = 0;
  for (const char c : text) {
    g |= static_cast<unsigned char>((c == 'G') | (c == 'g'));
    m |= static_cast<unsigned char>((c == 'M') | (c == 'm'));
    s |= static_cast<unsigned char>((c == 'S') | (c == 's'));
  }
  return (g ? nc_letter('G') : 0) | (m ? nc_letter('M') : 0) | (s ? nc_letter('S') : 0);
}

std::uint32_t nc_block::scan_letters() const {
  // One table look-up per character: most blocks are asked only this.
  static constexpr auto bit = [] {
    std::array<std::uint32_t, 256> t{};
    for (char c = 'A'; c <= 'Z'; ++c)
      t[static_cast<unsigned char>(c)] = t[static_cast<unsigned char>(c - 'A' + 'a')] = nc_letter(c);
    t[static_cast<unsigned char>('#')] = nc_variable_bit;
    return t;
  }();
  std::uint32_t may = 0;
  for (const char c : text) may |= bit[static_cast<unsigned char>(c)];
  letters_ = may;
  has_letters_ = true;
  return letters_;
}

bool nc_number(std::string_view s, double& out) {
  if (s.starts_with('+')) s.remove_prefix(1);
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return !s.empty() && ec == std::errc{} && p == s.data() + s.size();
}

std::vector<nc_word> split_nc_words(std::string_view line) {
  std::vector<nc_word> words;
  split_nc_words(line, words);
  return words;
}

std::uint32_t split_nc_words(std::string_view line, std::vector<nc_word>& words) {
  // The words are written over the vector's old ones, their values views into `line`: a
  // caller that splits every block of a long program allocates and copies nothing per block.
  std::size_t used = 0;
  std::size_t have = words.size();  // (kept: size() divides by the word's size, per word)
  std::uint32_t letters = 0;
  auto next = [&]() -> nc_word& {
    if (used == have) words.emplace_back(), ++have;
    nc_word& w = words[used++];
    w.expression = false;
    return w;
  };
  // Blanks skipped by hand: find_first_not_of calls memchr for each character.
  const std::size_t n = line.size();
  std::size_t i = 0;
  while (i < n && is_blank(line[i])) ++i;
  // A '#' in the skipped text of a bracket, an expression or a '%' line: a variable.
  const auto variables_in = [&](std::size_t from, std::size_t to) {
    if (to > from && std::memchr(line.data() + from, '#', to - from) != nullptr) letters |= nc_variable_bit;
  };
  if (i < n && line[i] == '%') {
    words.clear();
    variables_in(i, n);
    return letters;
  }
  while (i < n) {
    const char c = line[i];
    // A letter first: most characters of a block begin a word (or are its digits, read with it).
    if (is_letter(c)) {
      // The commonest word, a letter right before its number (X-12.5, G1): read and decoded
      // in one pass. Anything else (a keyword, blanks, a variable) takes the general way.
      if (i + 1 < n &&
          (is_digit(line[i + 1]) || line[i + 1] == '.' || line[i + 1] == '-' || line[i + 1] == '+')) {
        const std::size_t k = i + 1;
        const bool negative = line[k] == '-';
        const std::size_t v = line[k] == '+' || negative ? k + 1 : k;
        // Eight characters at a time (support/swar.hpp): a word's number ends within one or
        // two words of the text, with no loop over its digits. A second point after it
        // (`1.2.3`), eight digits on a side, or none, go the character way.
        swar::short_decimal sd;
        const char* const text = line.data();
        if (swar::read_short_decimal(text, text + v, text + n, sd) &&
            (sd.end == text + n || (*sd.end != '.' && !is_digit(*sd.end)))) [[likely]] {
          static constexpr double pow10[] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7};
          const auto d = static_cast<std::size_t>(sd.end - text);
          nc_word& w = next();
          const char a = upper(c);
          w.address = a;
          w.column = static_cast<int>(i) + 1;
          w.value = std::string_view(text + k, d - k);
          // At most fourteen digits: exact as a signed integer, and one correctly rounded
          // division, as decimal_scan's and from_chars' value.
          const double x = static_cast<double>(static_cast<std::int64_t>(sd.mantissa)) / pow10[sd.fraction];
          w.number = negative ? -x : x;
          w.point = sd.point;
          w.numeric = true;
          letters |= std::uint32_t{1} << (a - 'A');  // (a letter: nc_letter without its test)
          i = d;
          continue;
        }
        const decimal_scan number(line, v);
        const std::size_t d = number.end;
        if (d > v) {
          nc_word& w = next();
          const char a = upper(c);
          w.address = a;
          w.column = static_cast<int>(i) + 1;
          w.value = std::string_view(line.data() + k, d - k);
          w.numeric = number.value(negative, w.value, w.number, w.point);
          if (!w.numeric) w.number = 0, w.point = false;
          letters |= std::uint32_t{1} << (a - 'A');  // (a letter: nc_letter without its test)
          i = d;
          continue;
        }
      }
      std::size_t j = i;
      while (j < n && is_letter(line[j])) ++j;
      if (j - i > 1) {  // IF, GOTO, THEN, WHILE, ...: a keyword of macro statements
        i = j;
        continue;
      }
      std::size_t k = j;
      while (k < n && is_blank(line[k])) ++k;
      std::size_t v = k < n && (line[k] == '+' || line[k] == '-') ? k + 1 : k;
      std::size_t d = v;
      while (d < n && (is_digit(line[d]) || line[d] == '.')) ++d;
      bool expression = false;
      if (d > v) {
      } else if (k < n && (line[k] == '#' || line[k] == '[')) {
        d = k + 1;
        if (line[k] == '[')
          d = skip_brackets(line, k);
        else if (d < n && line[d] == '[')
          d = skip_brackets(line, d);
        else
          while (d < n && is_digit(line[d])) ++d;
        expression = true;
        variables_in(k, d);
      } else {
        i = j;  // a letter with no value
        continue;
      }
      nc_word& w = next();
      w.address = upper(c);
      w.column = static_cast<int>(i) + 1;
      w.value = line.substr(k, d - k);
      w.expression = expression;
      w.numeric = !expression && decode_number(w.value, w.number, w.point);
      if (!w.numeric) w.number = 0, w.point = false;
      letters |= nc_letter(w.address);
      i = d;
    } else if (c == '(') {
      const std::size_t close = line.find(')', i);
      if (close == std::string_view::npos) break;  // an unclosed comment runs to the end
      i = close + 1;
    } else if (c == ';') {
      // The rest is a comment to this reading, but not always to a control's: a '(' the split
      // skipped inside a bracket opens a comment the ';' stands in, and the code goes on after
      // its ')' (attack 70 F1: `IF [1 EQ 1(]; )] THEN #501=1.` writes #501). A '#' anywhere
      // after it counts: the bit may say more than macro_uses finds, never less.
      variables_in(i, n);
      break;
    } else if (c == '/') {
      i += i + 1 < n && is_digit(line[i + 1]) ? 2 : 1;  // block delete, optionally /1../9
    } else if (c == '[') {
      const std::size_t from = i;
      i = skip_brackets(line, i);
      variables_in(from, i);
    } else if (c == '#') {
      letters |= nc_variable_bit;
      for (++i; i < n && is_digit(line[i]);) ++i;  // a variable, not a word
    } else {
      ++i;
    }
  }
  words.resize(used);
  return letters;
}

}  // namespace twinpost
