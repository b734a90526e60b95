#pragma once
// The sub-commands of the twinpost tool. Each takes the arguments after its name and
// returns the process exit code. Only cli/ prints and parses options.
#include <string>
#include <vector>

namespace twinpost::cli {

using args = std::vector<std::string>;

int run_parse(const args& a);     ///< twinpost parse FILE [--json] [--dialect D]
int run_post(const args& a);      ///< twinpost post JOB --machine M -o DIR [--layout L]
int run_check(const args& a);     ///< twinpost check FILE... --machine M [--json]
int run_machines(const args& a);  ///< twinpost machines

}  // namespace twinpost::cli
