#!/usr/bin/env bash
# tests/program_name.sh SOURCE_DIR: the library never names the program. An error without a
# place gets "twinpost: error: " from the CLI alone (cli/cli_util.cpp, print_error); one at a
# place in an input is made by config_error::at and printed as it is. A "twinpost string
# literal in a library layer would print the name twice, or name a library user's program
# wrongly.
set -euo pipefail
src=${1:?usage: program_name.sh SOURCE_DIR}
cd "$src"
if grep -rn '"twinpost' support parser channels formats kinematics machines check post; then
  echo "program_name.sh: the library names the program (above); the CLI adds the name" >&2
  exit 1
fi
echo "program_name.sh: no program name in the library"
