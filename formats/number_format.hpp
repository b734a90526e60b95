#pragma once
// NC numbers: one rounding rule everywhere, no `-0.000`, whole numbers as `10.` when the
// control wants a decimal point, trailing zeros trimmed.
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
bool round_fixed(double v, int decimals, std::int64_t& n);

/// Appends a count made by round_fixed in `style` ("12.346", "10.", "-0.5").
void append_fixed(text_buffer& out, std::int64_t n, const number_style& style);
void append_fixed(std::string& out, std::int64_t n, const number_style& style);

/// Appends `v` rounded to the style's decimals (correctly rounded, as std::to_chars does).
void append_number(text_buffer& out, double v, const number_style& style);
void append_number(std::string& out, double v, const number_style& style);

/// `v` as a string in `style`.
std::string format_nc_number(double v, const number_style& style);

}  // namespace twinpost
