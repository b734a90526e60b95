#include "formats/number_format.hpp"

#include <charconv>
#include <cmath>

namespace twinpost {

namespace {

constexpr double pow10[] = {1, 10, 100, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};

// The exact rule: std::to_chars rounds the binary value correctly. Slow (it is a general
// printf engine), so it only settles the cases the fast path below cannot.
void append_exact(std::string& out, double v, const number_style& style) {
  char buf[64];
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

}  // namespace

void append_number(std::string& out, double v, const number_style& style) {
  // Fast path: scale to an integer count of the last decimal. The product carries an error
  // of about one unit in 1e16; unless its fraction sits within 1e-7 of a half, rounding it
  // decides exactly as rounding the binary value would, so the output equals to_chars'.
  int d = style.decimals;
  double scaled = v * pow10[d < 0 ? 0 : d > 9 ? 9 : d];
  double a = std::fabs(scaled);
  if (d < 0 || d > 9 || !(a < 1e15)) return append_exact(out, v, style);
  double fl = std::floor(a);
  double frac = a - fl;
  if (std::fabs(frac - 0.5) < 1e-7) return append_exact(out, v, style);
  unsigned long long n = static_cast<unsigned long long>(fl) + (frac > 0.5 ? 1 : 0);
  const bool zero = n == 0;  // whatever rounds to zero prints as zero, never "-0." or "-0"
  // Split into whole and fraction, drop the fraction's trailing zeros, write right to left.
  static constexpr unsigned long long scale[] = {1, 10, 100, 1000, 10000, 100000, 1000000,
                                                 10000000, 100000000, 1000000000};
  unsigned long long whole = n / scale[d];
  unsigned long long fraction = n % scale[d];
  int fraction_digits = d;
  while (fraction_digits > 0 && fraction % 10 == 0 && fraction != 0) {
    fraction /= 10;
    --fraction_digits;
  }
  if (fraction == 0) fraction_digits = 0;
  char buf[40];
  char* end = buf + sizeof buf;
  char* p = end;
  for (int k = 0; k < fraction_digits; ++k) {
    *--p = static_cast<char>('0' + fraction % 10);
    fraction /= 10;
  }
  if (fraction_digits > 0 || (d > 0 && style.trailing_point)) *--p = '.';
  do {
    *--p = static_cast<char>('0' + whole % 10);
    whole /= 10;
  } while (whole > 0);
  if (scaled < 0 && !zero) *--p = '-';
  out.append(p, static_cast<std::size_t>(end - p));
}

std::string format_nc_number(double v, const number_style& style) {
  std::string s;
  append_number(s, v, style);
  return s;
}

}  // namespace twinpost
