#include "formats/number_format.hpp"

#include <charconv>

namespace twinpost {

void append_number(std::string& out, double v, const number_style& style) {
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

std::string format_nc_number(double v, const number_style& style) {
  std::string s;
  append_number(s, v, style);
  return s;
}

}  // namespace twinpost
