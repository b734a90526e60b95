// twinpost machines: lists the built-in machine definitions, one per line, or
// prints the definition --machine NAME would use, to copy and edit.
#include <algorithm>
#include <cstdio>
#include <string>

#include <fmt/format.h>

#include "cli/command_table.hpp"
#include "cli/commands.hpp"
#include "cli/machine_dirs.hpp"
#include "machines/machine_loader.hpp"

namespace twinpost::cli {

namespace {

std::string machines_usage() {
  return "usage: " + command_usage("machines") +
         "\n"
         "\n"
         "Lists the built-in machine definitions: name, then description.\n"
         "--show NAME prints the definition that --machine NAME uses (TOML), to copy and edit.\n"
         "Pass a name to --machine, or a path to your own TOML file (see docs/machines.md).\n"
         "A name is looked up as NAME.toml in $XDG_CONFIG_HOME/twinpost/machines (default\n"
         "~/.config/twinpost/machines), then /etc/twinpost/machines, then the installation's\n"
         "share/twinpost/machines, then among the built-ins.\n";
}

}  // namespace

int run_machines(const args& a) {
  for (const std::string& arg : a) {
    if (arg == "--help" || arg == "-h") {
      std::fputs(machines_usage().c_str(), stdout);
      return 0;
    }
  }
  if (a.size() == 2 && a[0] == "--show") {
    const located_machine found = locate_machine(a[1]);  // an invalid file throws: exit 2
    std::fwrite(found.text.data(), 1, found.text.size(), stdout);
    // The script is a second file: a copy of this text works only with the script beside it.
    // A TOML comment, so that the output stays a machine file to copy and edit.
    if (!found.def.events.script.empty())
      fmt::print("{}# [events] script: {} (read from {}): copy it beside this file too\n",
                 found.text.empty() || found.text.back() == '\n' ? "" : "\n", found.def.events.script,
                 found.def.events.script_path);
    return 0;
  }
  if (!a.empty()) {
    const std::string& arg = a.front();
    fmt::print(stderr, "twinpost machines: {} '{}'\n\n{}",
               arg.starts_with('-') ? "unknown option" : "unexpected argument", arg, machines_usage());
    return 2;
  }
  const std::vector<machine_summary> all = builtin_machines();
  std::size_t width = 0;
  for (const machine_summary& m : all) width = std::max(width, m.name.size());
  for (const machine_summary& m : all) fmt::print("{:<{}}  {}\n", m.name, width, m.description);
  return 0;
}

}  // namespace twinpost::cli
