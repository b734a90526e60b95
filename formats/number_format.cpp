#include "formats/number_format.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>

namespace twinpost {

namespace {

constexpr std::int64_t ipow10[] = {1, 10, 100, 1000, 10000, 100000, 1000000, 10000000, 100000000, 1000000000};

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

namespace number_detail {

bool round_fixed_tie(double a, double scale, double p) {
  // Only an exact half in p needs the product's rounding error e (a * scale = p + e,
  // exactly, by fma); elsewhere |e| <= ulp(p)/2 cannot carry the true product across the
  // half. True when the true product is above the half, or on it with k odd (ties to even,
  // as to_chars does); the caller's k is then one too small.
  const double e = std::fma(a, scale, -p);
  return e > 0 || (e == 0 && (static_cast<std::int64_t>(p) & 1));
}

}  // namespace number_detail

namespace {

// Any decimals, any size: digits one division at a time.
char* write_fixed_general(char* out, std::int64_t n, const number_style& style) {
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
  std::memcpy(out, p, static_cast<std::size_t>(end - p));
  return out + (end - p);
}

// The eight digits of v < 10^8, zero-padded, as ASCII in one little-endian word (the first
// digit in the low byte), computed in registers: splitting 4-4, 2-2, 1-1 lane by lane.
std::uint64_t eight_digits(std::uint32_t v) {
  std::uint64_t x = (v / 10000) | (static_cast<std::uint64_t>(v % 10000) << 32);  // 4 + 4
  std::uint64_t hundreds = ((x * 5243) >> 19) & 0x0000007F0000007FULL;            // y / 100, y < 10^4
  x = hundreds | ((x - hundreds * 100) << 16);                                    // 2 + 2 per half
  std::uint64_t tens = ((x * 103) >> 10) & 0x000F000F000F000FULL;                 // y / 10, y < 100
  x = tens | ((x - tens * 10) << 8);                                              // 1 + 1
  return x | 0x3030303030303030ULL;
}

void store8(char* p, std::uint64_t w) {
  if constexpr (std::endian::native == std::endian::big) w = __builtin_bswap64(w);
  std::memcpy(p, &w, 8);
}

// D decimals, whole part below 10^8 (every coordinate a machine has), written straight into
// `out`: fixed-width digits cut to length, the same work whatever the number, no loop to
// mispredict and no digit stored twice. Anything else goes the general way.
template <int D>
char* write_fixed_d(char* p, std::int64_t n, const number_style& style) {
  const bool negative = n < 0;
  const std::uint64_t mag = negative ? 0 - static_cast<std::uint64_t>(n) : static_cast<std::uint64_t>(n);
  // Eight digits in all cover every coordinate a machine has at its decimals (12.345 at
  // three decimals is 12345); longer numbers go the general way.
  if (mag >= 100000000) return write_fixed_general(p, n, style);
  *p = '-';
  p += negative;
  // All digits from one conversion: the whole part the bytes before the last D, the
  // fraction the last D.
  const auto m = static_cast<std::uint32_t>(mag);
  const std::uint64_t all = eight_digits(m);
  if constexpr (D < 8) {
    // The whole part is the first 8 - D characters, i.e. the low bytes of the word.
    constexpr std::uint64_t whole_bytes = D == 0 ? ~0ULL : (1ULL << (8 * (8 - D))) - 1;
    // The eight digits' leading zeros are the word's low '0' bytes: the whole part is what
    // is left of its 8 - D digits, at least "0".
    const int leading = std::countr_zero(all ^ 0x3030303030303030ULL) / 8;  // 8 for m = 0
    const int whole = std::max(8 - D - leading, 1);
    store8(p, (all & whole_bytes) >> (8 * (8 - D - whole)));
    p += whole;
  } else {
    *p++ = '0';
  }
  if constexpr (D > 0) {
    const std::uint64_t fraction = D < 8 ? all >> (8 * (8 - D)) : all;  // D bytes, then zeros
    const std::uint64_t significant = fraction ^ (0x3030303030303030ULL >> (8 * (8 - D)));  // '0' -> 0
    if (significant != 0) {
      // Trailing zeros dropped: up to the last non-zero digit.
      const int kept = (63 - std::countl_zero(significant)) / 8 + 1;
      *p = '.';
      store8(p + 1, fraction);
      p += 1 + kept;
    } else if (style.trailing_point) {
      *p++ = '.';
    }
  }
  return p;
}

// Writes a count made by round_fixed at p (kMaxFixed bytes of room); returns the end.
char* write_fixed(char* p, std::int64_t n, const number_style& style) {
  switch (style.decimals) {
    case 0: return write_fixed_d<0>(p, n, style);
    case 1: return write_fixed_d<1>(p, n, style);
    case 2: return write_fixed_d<2>(p, n, style);
    case 3: return write_fixed_d<3>(p, n, style);
    case 4: return write_fixed_d<4>(p, n, style);
    case 5: return write_fixed_d<5>(p, n, style);
    case 6: return write_fixed_d<6>(p, n, style);
    case 7: return write_fixed_d<7>(p, n, style);
    case 8: return write_fixed_d<8>(p, n, style);
    default: return write_fixed_general(p, n, style);
  }
}

// "-9223372036854775808." and the 8-byte stores past the end of a short number fit.
constexpr std::size_t max_fixed = 48;

}  // namespace

void append_fixed(text_buffer& out, std::int64_t n, const number_style& style) {
  out.commit(write_fixed(out.room(max_fixed), n, style));
}

void append_fixed(std::string& out, std::int64_t n, const number_style& style) {
  char buf[max_fixed];
  out.append(buf, static_cast<std::size_t>(write_fixed(buf, n, style) - buf));
}

void append_number(text_buffer& out, double v, const number_style& style) {
  std::int64_t n;
  if (round_fixed(v, style.decimals, n)) return append_fixed(out, n, style);
  std::string exact;
  append_exact(exact, v, style);
  out += exact;
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
