#include "formats/number_format.hpp"

#include <charconv>
#include <cmath>
#include <cstring>

namespace twinpost {

namespace {

constexpr double pow10[] = {1, 10, 100, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};
constexpr std::int64_t ipow10[] = {1, 10, 100, 1000, 10000, 100000, 1000000, 10000000,
                                   100000000, 1000000000};

// "00" .. "99": two digits per division.
constexpr char two_digits[] =
    "0001020304050607080910111213141516171819202122232425262728293031323334353637383940414243444546474849"
    "5051525354555657585960616263646566676869707172737475767778798081828384858687888990919293949596979899";

// The general rule: std::to_chars rounds the binary value correctly. Only for values outside
// round_fixed's range.
void append_exact(std::string& out, double v, const number_style& style) {
  char buf[400];
  auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, style.decimals);
  char* begin = buf;
  char* end = r.ptr;
  if (style.decimals > 0) {
    while (end > begin && end[-1] == '0') --end;  // 12.500 -> 12.5, 10.000 -> 10.
    if (!style.trailing_point && end > begin && end[-1] == '.') --end;
  }
  // Whatever rounds to zero prints as zero, never "-0." or "-0".
  bool zero = true;
  for (char* p = begin; p < end; ++p)
    if (*p >= '1' && *p <= '9') zero = false;
  if (zero && *begin == '-') ++begin;
  out.append(begin, end);
}

// Writes `v` in decimal ending just before `end`; returns the first character.
char* write_digits(char* end, std::uint64_t v) {
  while (v >= 100) {
    std::uint64_t q = v / 100;
    std::memcpy(end -= 2, two_digits + 2 * (v - q * 100), 2);
    v = q;
  }
  if (v >= 10) {
    std::memcpy(end -= 2, two_digits + 2 * v, 2);
  } else {
    *--end = static_cast<char>('0' + v);
  }
  return end;
}

}  // namespace

bool round_fixed(double v, int decimals, std::int64_t& n) {
  if (decimals < 0 || decimals > 9) return false;
  double a = std::fabs(v);
  double scale = pow10[decimals];
  double p = a * scale;  // the product, rounded to a double
  if (!(p < 1e15)) return false;
  // p >= 0: truncation is floor, and exact (p < 2^52).
  auto k = static_cast<std::int64_t>(p);
  double frac = p - static_cast<double>(k);
  k += frac > 0.5;  // no branch: the fraction is anyone's guess
  if (frac == 0.5) [[unlikely]] {
    // Only an exact half in p needs the product's rounding error e (a * scale = p + e,
    // exactly, by fma); elsewhere |e| <= ulp(p)/2 cannot carry the true product across the
    // half. A true tie goes to even, as to_chars does.
    double e = std::fma(a, scale, -p);
    if (e > 0 || (e == 0 && (k & 1))) ++k;
  }
  n = v < 0 ? -k : k;
  return true;
}

namespace {

// Any decimals, any size: digits one division at a time.
void append_fixed_general(std::string& out, std::int64_t n, const number_style& style) {
  int d = style.decimals;
  std::uint64_t mag = n < 0 ? 0 - static_cast<std::uint64_t>(n) : static_cast<std::uint64_t>(n);
  auto scale = static_cast<std::uint64_t>(ipow10[d]);
  std::uint64_t whole = mag / scale;
  std::uint64_t fraction = mag - whole * scale;
  char buf[48];
  char* end = buf + sizeof buf;
  char* p = end;
  if (fraction != 0) {
    // Drop the fraction's trailing zeros, then pad it to its width with leading zeros.
    int digits = d;
    while (fraction % 10 == 0) {
      fraction /= 10;
      --digits;
    }
    char* f = write_digits(end, fraction);
    p = end - digits;
    while (f > p) *--f = '0';
    *--p = '.';
  } else if (d > 0 && style.trailing_point) {
    *--p = '.';
  }
  p = write_digits(p, whole);
  if (n < 0) *--p = '-';
  out.append(p, static_cast<std::size_t>(end - p));
}

// The eight digits of v < 10^8, zero-padded, at p[0..8): four pairs, no loop.
void eight_digits(char* p, std::uint32_t v) {
  const std::uint32_t hi = v / 10000, lo = v % 10000;
  std::memcpy(p, two_digits + 2 * (hi / 100), 2);
  std::memcpy(p + 2, two_digits + 2 * (hi % 100), 2);
  std::memcpy(p + 4, two_digits + 2 * (lo / 100), 2);
  std::memcpy(p + 6, two_digits + 2 * (lo % 100), 2);
}

// Decimal digits of 0 < v < 10^8 (1 for 0), without a branch.
int digit_count(std::uint32_t v) {
  return 1 + (v >= 10) + (v >= 100) + (v >= 1000) + (v >= 10000) + (v >= 100000) +
         (v >= 1000000) + (v >= 10000000);
}

// D decimals, whole part below 10^8 (every coordinate a machine has): fixed-width digit
// pairs cut to length, so the work is the same whatever the number, with no loops to
// mispredict. Anything else goes the general way.
template <int D>
void append_fixed_d(std::string& out, std::int64_t n, const number_style& style) {
  constexpr std::uint64_t scale = ipow10[D];
  const bool negative = n < 0;
  const std::uint64_t mag = negative ? 0 - static_cast<std::uint64_t>(n) : static_cast<std::uint64_t>(n);
  const std::uint64_t whole = mag / scale;
  if (whole >= 100000000) return append_fixed_general(out, n, style);
  const auto fraction = static_cast<std::uint32_t>(mag - whole * scale);
  char digits[16];
  char buf[40];
  char* p = buf;
  *p = '-';
  p += negative;
  eight_digits(digits, static_cast<std::uint32_t>(whole));
  const int count = digit_count(static_cast<std::uint32_t>(whole));
  std::memcpy(p, digits + 8 - count, 8);  // eight bytes copied, `count` of them kept
  p += count;
  if constexpr (D > 0) {
    if (fraction != 0) {
      *p++ = '.';
      eight_digits(digits, fraction);
      std::memcpy(p, digits + 8 - D, D);
      p += D;
      while (p[-1] == '0') --p;  // 12.500 -> 12.5 (the fraction is not zero: a digit stays)
    } else if (style.trailing_point) {
      *p++ = '.';
    }
  }
  out.append(buf, static_cast<std::size_t>(p - buf));
}

}  // namespace

void append_fixed(std::string& out, std::int64_t n, const number_style& style) {
  switch (style.decimals) {
    case 0: return append_fixed_d<0>(out, n, style);
    case 1: return append_fixed_d<1>(out, n, style);
    case 2: return append_fixed_d<2>(out, n, style);
    case 3: return append_fixed_d<3>(out, n, style);
    case 4: return append_fixed_d<4>(out, n, style);
    case 5: return append_fixed_d<5>(out, n, style);
    case 6: return append_fixed_d<6>(out, n, style);
    case 7: return append_fixed_d<7>(out, n, style);
    case 8: return append_fixed_d<8>(out, n, style);
    default: return append_fixed_general(out, n, style);
  }
}

void append_number(std::string& out, double v, const number_style& style) {
  std::int64_t n;
  if (round_fixed(v, style.decimals, n)) return append_fixed(out, n, style);
  append_exact(out, v, style);
}

std::string format_nc_number(double v, const number_style& style) {
  std::string s;
  append_number(s, v, style);
  return s;
}

}  // namespace twinpost
