#!/usr/bin/env bash
# scripts/format.sh [--check] [SOURCE_DIR]: applies .clang-format to every C++ source of the
# project (clang-format 14, Debian 12's; other versions format a few constructs differently),
# or with --check lists the files that do not follow it and fails. ctest `format` runs the
# check; it skips (77) where clang-format-14 is not installed. New files count before they are
# added to git (a file formatted only once committed failed CI once).
set -euo pipefail
check=0
if [[ ${1:-} == --check ]]; then check=1; shift; fi
src=${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}
cd "$src"
tool=$(command -v clang-format-14 || true)
if [[ -z $tool ]]; then
  echo "format.sh: clang-format-14 not installed (apt-get install clang-format-14): not checked"
  exit 77
fi
mapfile -t files < <(git ls-files --cached --others --exclude-standard -- '*.cpp' '*.hpp' 2>/dev/null ||
                     find support machines parser channels kinematics formats machining check analysis post cli tests fuzz bench \
                       -name '*.[ch]pp')
if ((check == 0)); then
  "$tool" -i "${files[@]}"
  exit 0
fi
bad=0
for f in "${files[@]}"; do
  if ! "$tool" --dry-run -Werror "$f" >/dev/null 2>&1; then
    echo "format.sh: $f does not follow .clang-format (run scripts/format.sh)"
    bad=1
  fi
done
((bad == 0)) && echo "format.sh: ${#files[@]} files follow .clang-format"
exit "$bad"
