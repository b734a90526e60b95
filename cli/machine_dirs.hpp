#pragma once
// The folders `--machine NAME` looks in for NAME.toml before the built-ins, in order:
//   1. $XDG_CONFIG_HOME/twinpost/machines (or ~/.config/twinpost/machines): the user's own;
//   2. /etc/twinpost/machines: the site's;
//   3. ../share/twinpost/machines beside the binary: the installed copies of the built-ins.
#include <string>
#include <vector>

#include "machines/machine_search.hpp"

namespace twinpost::cli {

/// The search folders for this process (from its environment and its own path).
std::vector<std::string> machine_dirs();

/// find_machine() over machine_dirs().
located_machine locate_machine(const std::string& name_or_path);

}  // namespace twinpost::cli
