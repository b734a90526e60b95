#pragma once
// Finding a machine definition by name: the user's and the system's machine folders first,
// then the definitions compiled into the binary. The folders are the caller's to choose
// (the command-line tool passes $XDG_CONFIG_HOME/twinpost/machines, /etc/twinpost/machines
// and the installation's share/twinpost/machines, in that order: docs/machines.md).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "machines/machine.hpp"
#include "support/errors.hpp"

namespace twinpost {

/// A machine definition and where it came from.
struct located_machine {
  machine def;
  std::string origin;  ///< the file it was read from, or "built-in"
  std::string text;    ///< the TOML text as read
};

/// Finds `name_or_path`. A path (it holds a '/' or ends in ".toml") is read as given. A
/// name is looked up as NAME.toml in each of `dirs` in turn, then among the built-ins, and
/// last as a file of that name in the working folder. Throws config_error when nothing is
/// found (naming every place looked in) or the definition is invalid.
located_machine find_machine(std::string_view name_or_path, const std::vector<std::string>& dirs);

/// The built-in definition's TOML text, if `name` is a built-in machine.
std::optional<std::string_view> builtin_machine_text(std::string_view name);

}  // namespace twinpost
