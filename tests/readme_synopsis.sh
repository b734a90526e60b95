#!/usr/bin/env bash
# README's command synopsis is `twinpost --help`, line for line: the block between the
# markers below in README.md must equal what the command table (cli/command_table.cpp)
# prints. On a difference, paste `twinpost --help` into the block.
#   usage: readme_synopsis.sh README.md path/to/twinpost
set -euo pipefail
readme=$1 bin=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/twinpost-readme-XXXXXX")
trap 'rm -rf "$work"' EXIT

# The lines inside the fenced block between the markers, without the fence lines.
awk '/^<!-- synopsis: begin/ { on = 1; next }
     /^<!-- synopsis: end/   { on = 0 }
     on && !/^```/' "$readme" >"$work/readme"
if [ ! -s "$work/readme" ]; then
  echo "readme_synopsis: no block between <!-- synopsis: begin --> and <!-- synopsis: end --> in $readme" >&2
  exit 1
fi
"$bin" --help >"$work/help"
if ! diff -u --label "README.md synopsis" --label "twinpost --help" "$work/readme" "$work/help"; then
  echo "readme_synopsis: README.md's synopsis differs from 'twinpost --help' (above)" >&2
  exit 1
fi
