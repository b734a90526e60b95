#pragma once
// Eight characters at a time (SWAR: SIMD within a register): the digits of a short decimal
// number found and combined in a few word operations instead of a loop over characters. Plain
// text, no grammar: shared by the CL reader's numbers (parser/detail/lexical.hpp) and the NC
// word split (nc/nc_words.cpp), the two places that read every number of a job.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace twinpost::swar {

// Eight characters as one little-endian word (the first in the low byte).
inline std::uint64_t load8(const char* p) {
  std::uint64_t w;
  std::memcpy(&w, p, 8);
  if constexpr (std::endian::native == std::endian::big) w = __builtin_bswap64(w);
  return w;
}
// A flag in each byte of `w` that is no digit, exact up to and including the first such byte
// (and past a '.', which takes no carry further: 0x2E ^ 0x30 + 6 < 0x100). A digit is
// 0x30..0x39: its high nibble 3 and its low nibble below 10 (+6 carries no further). A byte
// after the first non-digit may take a carry from it, which cannot move that first one.
inline std::uint64_t non_digits(std::uint64_t w) {
  const std::uint64_t x = w ^ 0x3030303030303030ULL;
  return (x | (x + 0x0606060606060606ULL)) & 0xF0F0F0F0F0F0F0F0ULL;
}
// How many of the eight characters in `w` are digits before the first that is not.
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

// Up to eight characters from `p` (not past `last`) as one word, the first in the low byte and
// zero bytes (no digit) after `last`. With fewer than eight left, the eight that end at `last`
// are read when the text has them (it starts at `begin`) and shifted down: never a byte outside
// [begin, last).
inline std::uint64_t load_upto8(const char* begin, const char* p, const char* last) {
  const auto n = static_cast<std::size_t>(last - p);
  if (n >= 8) return load8(p);
  if (n == 0) return 0;
  if (last - begin >= 8) return load8(last - 8) >> (8 * (8 - n));
  std::uint64_t w = 0;
  for (std::size_t k = 0; k < n; ++k) w |= std::uint64_t{static_cast<unsigned char>(p[k])} << (8 * k);
  return w;
}

/// A short unsigned decimal (`43.9904`, `154.`, `.5`, `250`): its digits as one integer, how
/// many of them follow the point, and where it ends.
struct short_decimal {
  std::uint64_t mantissa = 0;  ///< every digit, the point left out (at most fourteen: exact)
  int fraction = 0;            ///< digits after the point
  bool point = false;          ///< a point is written ("1." and "1.5", not "1")
  const char* end = nullptr;   ///< the first character after the number
};

/// Reads the number that starts at `p` (after any sign) in a text that starts at `begin`
/// (begin <= p) and ends at `last`: up to eight characters as one word, the point taken out of
/// it and its digits combined at once; a fraction that goes on past the word takes one more
/// word. False, `out` unset, where it hands on to a reading character by character: eight
/// digits or more on either side of the point, no digit at all ("." alone, a letter).
[[gnu::always_inline]] inline bool read_short_decimal(const char* begin, const char* p, const char* last,
                                                      short_decimal& out) {
  const std::uint64_t w = load_upto8(begin, p, last);
  const std::uint64_t bad = non_digits(w);
  if (bad == 0) return false;  // eight digits or more before the point
  const int whole = std::countr_zero(bad) / 8;
  // The byte after the digits is the text's (a byte past `last` reads as 0, no point).
  if (((w >> (8 * whole)) & 0xFF) != '.') {
    if (whole == 0) return false;
    out.mantissa = digits_value(w, whole);
    out.fraction = 0;
    out.point = false;
    out.end = p + whole;
    return true;
  }
  const std::uint64_t rest = bad & ~(0xFFULL << (8 * whole));  // the point's flag off
  if (rest != 0 || last - p == 8) {                            // the number ends within the word
    const int end = rest != 0 ? std::countr_zero(rest) / 8 : 8;
    if (end == 1) return false;                                         // "." alone
    const std::uint64_t below = (std::uint64_t{1} << (8 * whole)) - 1;  // whole <= 7
    out.mantissa = digits_value((w & below) | ((w >> 8) & ~below), end - 1);
    out.fraction = end - 1 - whole;
    out.end = p + end;
  } else {  // the fraction goes on in the next word
    static constexpr std::uint64_t ipow10[] = {1, 10, 100, 1000, 10000, 100000, 1000000, 10000000};
    const std::uint64_t f = load_upto8(begin, p + whole + 1, last);
    const int fraction = leading_digits(f);
    if (fraction == 8) return false;  // eight digits or more after it
    std::uint64_t m = whole ? digits_value(w, whole) : 0;
    if (fraction) m = m * ipow10[fraction] + digits_value(f, fraction);
    out.mantissa = m;
    out.fraction = fraction;
    out.end = p + whole + 1 + fraction;
  }
  out.point = true;
  return true;
}

}  // namespace twinpost::swar
