#pragma once
// Plain lexical pieces of CL, with no X3 in them: shared by the grammar's primitives
// (number_parser.hpp, text_major_parser.hpp) and the fast path for numeric records
// (fast_record.cpp), so that both read characters, numbers and text majors alike.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string_view>

#include "support/ascii.hpp"
#include "support/swar.hpp"

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
// Runs of digits are read eight at a time where eight characters remain.
inline const char* fast_decimal(const char* p, const char* last, double& value) {
  static constexpr double pow10[] = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                     1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
  static constexpr unsigned long long ipow10[] = {1,      10,      100,      1000,     10000,
                                                  100000, 1000000, 10000000, 100000000};
  // Digits first, counted afterwards: more than 15 go to from_chars, so the unsigned
  // arithmetic here may wrap on a long number without harm.
  unsigned long long mantissa = 0;
  const auto run = [&](const char*& q) {
    while (last - q >= 8) {
      const std::uint64_t w = swar::load8(q);
      const int n = swar::leading_digits(w);
      if (n == 0) return;
      mantissa = mantissa * ipow10[n] + swar::digits_value(w, n);
      q += n;
      if (n < 8) return;
    }
    while (q != last && static_cast<unsigned>(*q - '0') < 10)
      mantissa = mantissa * 10 + static_cast<unsigned>(*q++ - '0');
  };
  const char* int_begin = p;
  run(p);
  int digits = static_cast<int>(p - int_begin), fraction = 0;
  if (p != last && *p == '.') {
    const char* frac_begin = ++p;
    run(p);
    fraction = static_cast<int>(p - frac_begin);
    digits += fraction;
  }
  if (digits > 15) return nullptr;
  if (digits == 0) return nullptr;
  if (p != last && (*p == 'e' || *p == 'E')) return nullptr;
  value = static_cast<double>(mantissa) / pow10[fraction];
  return p;
}

/// fast_decimal for a number inside a text that starts at `begin` (begin <= p), for the common
/// CL number: up to eight characters (`43.9904`, `154.0000`, `250`) are read as one word, the
/// point taken out of it and its digits combined at once; a fraction that goes on past the word
/// (`0.3206994`) takes one more word. Never a loop over characters; seven digits or more on
/// either side of the point go to fast_decimal. The same value (digits / 10^fraction, one
/// correctly rounded division) and the same end as fast_decimal, or nullptr where it hands on.
/// Always inline: the fast path reads three numbers a record through it, and a call each cost
/// a tenth of the reading.
[[gnu::always_inline]] inline const char* fast_decimal_in(const char* begin, const char* p, const char* last,
                                                          double& value) {
  static constexpr double pow10[] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7};
  swar::short_decimal n;
  // Eight digits or more on a side to fast_decimal, which finds no number in "." alone or a
  // letter (nullptr) as this would.
  if (!swar::read_short_decimal(begin, p, last, n)) return fast_decimal(p, last, value);
  if (n.end != last && (*n.end | 0x20) == 'e') return nullptr;  // 'e' or 'E': an exponent
  // At most fourteen digits: exact as a signed integer, whose conversion is one instruction.
  value = static_cast<double>(static_cast<std::int64_t>(n.mantissa)) / pow10[n.fraction];
  return n.end;
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
