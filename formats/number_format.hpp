#pragma once
// NC numbers: one rounding rule everywhere, no `-0.000`, whole numbers as `10.` when the
// control wants a decimal point, trailing zeros trimmed.
#include <cmath>
#include <cstdint>
#include <string>

#include "formats/text_buffer.hpp"

namespace twinpost {

struct number_style {
  int decimals = 3;
  bool trailing_point = true;  ///< "10." (true) or "10" (false) for whole numbers
};

/// `v` rounded to `decimals` places as a count of the last place (12.3456 at 3 -> 12346),
/// exactly as std::to_chars rounds the binary value (ties to even); never -0. False when
/// the value is out of the fast range (|v| * 10^decimals >= 1e15, or decimals not 0..9).
/// Inline: every written coordinate comes through here, and the call cost a third of it.
inline bool round_fixed(double v, int decimals, std::int64_t& n);

namespace number_detail {
/// round_fixed's exact half: true when the true product a * scale (p rounded) lies above it, or
/// on it with an odd count (ties to even).
bool round_fixed_tie(double a, double scale, double p);
inline constexpr double pow10[] = {1, 10, 100, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};
}  // namespace number_detail

/// One unit of a word written with `decimals` decimals (0 to 9): 10^-decimals.
inline double decimal_unit(int decimals) {
  return 1.0 / number_detail::pow10[decimals < 0 ? 0 : decimals > 9 ? 9 : decimals];
}

inline bool round_fixed(double v, int decimals, std::int64_t& n) {
  if (decimals < 0 || decimals > 9) return false;
  const double a = std::fabs(v);
  const double scale = number_detail::pow10[decimals];
  const double p = a * scale;  // the product, rounded to a double
  if (!(p < 1e15)) return false;
  // p >= 0: truncation is floor, and exact (p < 2^52).
  auto k = static_cast<std::int64_t>(p);
  const double frac = p - static_cast<double>(k);
  k += frac > 0.5;  // no branch: the fraction is anyone's guess
  if (frac == 0.5) [[unlikely]]
    k += number_detail::round_fixed_tie(a, scale, p);
  n = v < 0 ? -k : k;
  return true;
}

/// Appends a count made by round_fixed in `style` ("12.346", "10.", "-0.5").
void append_fixed(text_buffer& out, std::int64_t n, const number_style& style);
void append_fixed(std::string& out, std::int64_t n, const number_style& style);

/// Appends `v` rounded to the style's decimals (correctly rounded, as std::to_chars does).
void append_number(text_buffer& out, double v, const number_style& style);
void append_number(std::string& out, double v, const number_style& style);

/// `v` as a string in `style`.
std::string format_nc_number(double v, const number_style& style);

}  // namespace twinpost
