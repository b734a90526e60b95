#pragma once
// Loading and validating machine definitions (TOML). Errors throw config_error with the
// file, line and column of the offending value.
#include <string>
#include <string_view>
#include <vector>

#include "machines/machine.hpp"
#include "support/errors.hpp"

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

}  // namespace twinpost
