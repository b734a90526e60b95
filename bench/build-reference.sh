#!/usr/bin/env bash
# bench/build-reference.sh [DIR]: builds the pinned reference build of docs/benchmark.md
# (commit e9f2573, 2026-11-22, the post before the self-check's cycle time and spindle rules)
# into DIR (default /tmp/twinpost-reference) and prints the two arguments run.sh wants for it:
#   bench/run.sh --mode post $(bench/build-reference.sh) ...
# i.e. `--baseline DIR/build/twinpost --baseline-mill DIR/bench/bench-mill.toml` (that build
# reads the mill machine file as it was then). Quick when it is already built.
set -euo pipefail
pinned=e9f2573
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
dir=${1:-/tmp/twinpost-reference}
if [[ ! -d $dir/.git && ! -f $dir/.git ]]; then
  git -C "$repo" worktree add --detach "$dir" "$pinned" >&2
fi
[[ $(git -C "$dir" rev-parse --short=7 HEAD) == "$pinned" ]] ||
  { echo "build-reference.sh: $dir is not at $pinned" >&2; exit 1; }
if [[ ! -x $dir/build/twinpost ]]; then
  echo "building the reference $pinned into $dir/build ..." >&2
  launcher=()
  if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
  cmake -S "$dir" -B "$dir/build" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" >/dev/null
  cmake --build "$dir/build" --target twinpost -j "$(nproc)" >/dev/null
fi
echo "--baseline $dir/build/twinpost --baseline-mill $dir/bench/bench-mill.toml"
