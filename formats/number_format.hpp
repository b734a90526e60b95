#pragma once
// NC numbers: one rounding rule everywhere, no `-0.000`, whole numbers as `10.` when the
// control wants a decimal point, trailing zeros trimmed.
#include <string>

namespace twinpost {

struct number_style {
  int decimals = 3;
  bool trailing_point = true;  ///< "10." (true) or "10" (false) for whole numbers
};

/// Appends `v` rounded to the style's decimals (correctly rounded, as std::to_chars does).
void append_number(std::string& out, double v, const number_style& style);

/// `v` as a string in `style`.
std::string format_nc_number(double v, const number_style& style);

}  // namespace twinpost
