#pragma once
// The sub-commands of the twinpost tool. Each takes the arguments after its name and
// returns the process exit code. Only cli/ prints and parses options.
#include <string>
#include <vector>

namespace twinpost::cli {

using args = std::vector<std::string>;

// Their synopses live in one place, the table of cli/command_table.cpp.
int run_parse(const args& a);
int run_post(const args& a);
int run_check(const args& a);
int run_machines(const args& a);
int run_kin(const args& a);
int run_timeline(const args& a);

}  // namespace twinpost::cli
