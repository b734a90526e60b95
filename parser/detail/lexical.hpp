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
namespace swar {
// Eight characters as one little-endian word (the first in the low byte).
inline std::uint64_t load8(const char* p) {
  std::uint64_t w;
  std::memcpy(&w, p, 8);
  if constexpr (std::endian::native == std::endian::big) w = __builtin_bswap64(w);
  return w;
}
// How many of the eight characters in `w` are digits before the first that is not. A digit is
// 0x30..0x39: its high nibble 3 and its low nibble below 10 (+6 carries no further). A byte after
// the first non-digit may take a carry from it, which cannot move that first one.
// A flag in each byte of `w` that is no digit, exact up to and including the first such byte
// (and past a '.', which takes no carry further: 0x2E ^ 0x30 + 6 < 0x100).
inline std::uint64_t non_digits(std::uint64_t w) {
  const std::uint64_t x = w ^ 0x3030303030303030ULL;
  return (x | (x + 0x0606060606060606ULL)) & 0xF0F0F0F0F0F0F0F0ULL;
}
inline int leading_digits(std::uint64_t w) {
  const std::uint64_t bad = non_digits(w);
  return bad == 0 ? 8 : std::countr_zero(bad) / 8;
}
// The value of the first `n` (1..8) digits of `w`: their values moved to the top `n` bytes, with
// zeros (leading zero digits) below, then combined pairwise, in fours and in eights (the method
// of Lemire's fast_float). The subtraction may borrow only out of a byte that is no digit,
// always into the bytes after it, which the shift drops.
inline std::uint64_t digits_value(std::uint64_t w, int n) {
  w = (w - 0x3030303030303030ULL) << (8 * (8 - n));
  w = (w * 10) + (w >> 8);  // pairs
  w = (((w & 0x000000FF000000FFULL) * 0x000F424000000064ULL) +
       (((w >> 16) & 0x000000FF000000FFULL) * 0x0000271000000001ULL)) >>
      32;
  return w;
}
}  // namespace swar

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

// Up to eight characters from `p` (not past `last`) as one word, the first in the low byte and
// zero bytes (no digit) after `last`. With fewer than eight left, the eight that end at `last`
// are read when the text has them (it starts at `begin`) and shifted down: never a byte outside
// [begin, last).
inline std::uint64_t load_upto8(const char* begin, const char* p, const char* last) {
  const auto n = static_cast<std::size_t>(last - p);
  if (n >= 8) return swar::load8(p);
  if (n == 0) return 0;
  if (last - begin >= 8) return swar::load8(last - 8) >> (8 * (8 - n));
  std::uint64_t w = 0;
  for (std::size_t k = 0; k < n; ++k) w |= std::uint64_t{static_cast<unsigned char>(p[k])} << (8 * k);
  return w;
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
  static constexpr std::uint64_t ipow10[] = {1, 10, 100, 1000, 10000, 100000, 1000000, 10000000};
  const std::uint64_t w = load_upto8(begin, p, last);
  const std::uint64_t bad = swar::non_digits(w);
  if (bad == 0) return fast_decimal(p, last, value);  // eight digits or more before the point
  const int whole = std::countr_zero(bad) / 8;
  std::uint64_t mantissa;
  int fraction;
  // The byte after the digits is the text's (a byte past `last` reads as 0, no point).
  if (((w >> (8 * whole)) & 0xFF) == '.') {
    const std::uint64_t rest = bad & ~(0xFFULL << (8 * whole));  // the point's flag off
    if (rest != 0 || last - p == 8) {                            // the number ends within the word
      const int end = rest != 0 ? std::countr_zero(rest) / 8 : 8;
      if (end == 1) return nullptr;                                       // "." alone
      const std::uint64_t below = (std::uint64_t{1} << (8 * whole)) - 1;  // whole <= 7
      mantissa = swar::digits_value((w & below) | ((w >> 8) & ~below), end - 1);
      fraction = end - 1 - whole;
      p += end;
    } else {  // the fraction goes on in the next word
      const std::uint64_t f = load_upto8(begin, p + whole + 1, last);
      fraction = swar::leading_digits(f);
      if (fraction == 8) return fast_decimal(p, last, value);  // eight digits or more after it
      mantissa = whole ? swar::digits_value(w, whole) : 0;
      if (fraction) mantissa = mantissa * ipow10[fraction] + swar::digits_value(f, fraction);
      p += whole + 1 + fraction;
    }
  } else {
    if (whole == 0) return nullptr;
    mantissa = swar::digits_value(w, whole);
    fraction = 0;
    p += whole;
  }
  if (p != last && (*p | 0x20) == 'e') return nullptr;  // 'e' or 'E': an exponent
  // At most fourteen digits: exact as a signed integer, whose conversion is one instruction.
  value = static_cast<double>(static_cast<std::int64_t>(mantissa)) / pow10[fraction];
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
