#pragma once
// Loading and validating machine definitions (TOML). Errors throw config_error with the
// file, line and column of the offending value.
#include <string>
#include <string_view>
#include <vector>

#include "machines/machine.hpp"

namespace twinpost {

/// Parses and validates a machine definition from TOML text; `source` names it in errors.
machine parse_machine(std::string_view toml_text, std::string_view source);

/// Loads `name_or_path`: a built-in machine name, or else a path to a TOML file
/// (find_machine with no search folders).
machine load_machine(std::string_view name_or_path);

/// Names and one-line descriptions of the built-in machines, sorted by name.
struct machine_summary {
  std::string name;
  std::string description;
};
std::vector<machine_summary> builtin_machines();

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
