#pragma once
// The templates of a machine file (tool_call, clamp, dwell, header and footer lines,
// program line, file name) are fmt format strings with named placeholders only.
#include <string>
#include <string_view>

namespace twinpost {

/// The values a template (tool_call, clamp, header block, ...) may name as {program},
/// {name}, {channel}, {max}, {tool}, {offset}, {seconds}, {ms} and {rpm}.
struct template_args {
  int program = 0;       ///< program (O) number
  std::string name;      ///< program name (sanitized PARTNO)
  int channel = 1;       ///< channel number
  double max = 0;        ///< spindle speed clamp
  int tool = 0;          ///< tool number
  int offset = 0;        ///< tool offset number
  double seconds = 0;    ///< dwell time in seconds
  int ms = 0;            ///< dwell time in milliseconds
  double rpm = 0;        ///< spindle speed
};

/// Formats template `tpl` with `a`; throws fmt::format_error for a bad template, including
/// a positional placeholder ({} or {0}), which would silently pick the wrong value.
std::string format_template(std::string_view tpl, const template_args& a);

/// The sample values every template is formatted with once when a machine loads.
template_args sample_template_args();

}  // namespace twinpost
