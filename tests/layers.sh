#!/usr/bin/env bash
# tests/layers.sh SOURCE_DIR: every #include "layer/..." of the library and the CLI must name
# its own layer or one below it (docs/design.md, "Layers"). The CMake libraries enforce the
# same graph at link time; this catches a header-only include that the linker never sees.
set -euo pipefail
src=${1:?usage: layers.sh SOURCE_DIR}
declare -A allowed=(
  [support]="support"
  [nc]="nc support"
  [machines]="machines support"
  [scripting]="scripting support"
  [parser]="parser support"
  [channels]="channels parser machines support"
  [kinematics]="kinematics machines support"
  [formats]="formats parser machines support"
  [machining]="machining scripting formats kinematics channels parser machines nc support"
  [check]="check machines nc support"
  [analysis]="analysis check kinematics parser machines nc support"
  [post]="post analysis machining scripting formats kinematics check channels parser machines nc support"
  [cli]="cli post analysis machining scripting formats kinematics check channels parser machines nc support"
)
bad=0
for layer in "${!allowed[@]}"; do
  while IFS= read -r -d '' file; do
    while IFS=: read -r line inc; do
      dep=${inc#*\"}
      dep=${dep%%/*}
      [[ $dep == "$inc" || -z $dep ]] && continue
      if [[ " ${allowed[$layer]} " != *" $dep "* ]]; then
        echo "${file#"$src"/}:$line: $layer/ may not include $dep/ (${inc})"
        bad=1
      fi
    done < <(grep -n '^#include "' "$file" | sed 's/:#include /:/' || true)
  done < <(find "$src/$layer" -name '*.[ch]pp' -print0)
done
if ((bad)); then
  echo "layers.sh: includes that cross the layers (see docs/design.md)" >&2
  exit 1
fi
echo "layers.sh: every include follows the layer graph"
