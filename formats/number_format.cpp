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
  // Digits from the right into a small buffer, then one append.
  char buf[40];
  char* end = buf + sizeof buf;
  char* p = end;
  int k = 0;
  bool in_fraction_zeros = true;  // trailing zeros of the fraction are dropped
  for (; k < d; ++k) {
    char c = static_cast<char>('0' + n % 10);
    n /= 10;
    if (in_fraction_zeros && c == '0') continue;
    in_fraction_zeros = false;
    *--p = c;
  }
  if (p != end) *--p = '.';
  else if (d > 0 && style.trailing_point) *--p = '.';
  do {
    *--p = static_cast<char>('0' + n % 10);
    n /= 10;
  } while (n > 0);
  // Whatever rounds to zero prints as zero, never "-0." or "-0".
  bool zero = true;
  for (char* q = p; q < end; ++q)
    if (*q >= '1' && *q <= '9') zero = false;
  if (scaled < 0 && !zero) *--p = '-';
  out.append(p, static_cast<std::size_t>(end - p));
}

std::string format_nc_number(double v, const number_style& style) {
  std::string s;
  append_number(s, v, style);
  return s;
}

}  // namespace twinpost
