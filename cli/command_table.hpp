#pragma once
// The one table of twinpost's commands: main() dispatches through it, `twinpost --help`
// prints it, and the man page twinpost(1) is generated from it (`twinpost --man`, run by
// the build), so the three can never disagree.
#include <span>
#include <string>
#include <string_view>

#include "cli/commands.hpp"

namespace twinpost::cli {

struct command_entry {
  const char* name;      ///< "post"
  const char* synopsis;  ///< what follows the name: "JOB --machine M -o DIR [--layout L] ..."
  const char* summary;   ///< one line for the usage text
  const char* details;   ///< a paragraph for the man page
  int (*run)(const args&);
};

/// Every command, in the order the usage text lists them.
std::span<const command_entry> command_table();

/// "twinpost NAME SYNOPSIS" of the command `name` (which must be in the table): the first
/// line of the command's own --help.
std::string command_usage(std::string_view name);

/// The usage text of `twinpost --help`.
std::string usage_text();

/// The man page twinpost(1) in roff (man macros).
std::string man_page();

}  // namespace twinpost::cli
