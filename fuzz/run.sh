#!/usr/bin/env bash
# Builds the libFuzzer targets with CMake (TWINPOST_FUZZ=ON, clang, ASan + UBSan) into
# build-fuzz/ and runs one of them on one core.
#   fuzz/run.sh TARGET [libFuzzer flags]    TARGET: cl_reader | post | check | script | events
#   fuzz/run.sh post -max_total_time=3600   an hour (default: -runs=1000000)
#   FUZZ_BUILD_ONLY=1 fuzz/run.sh TARGET    build only
# The working corpus is fuzz/corpus/TARGET/ (ignored by git), seeded from the samples, the
# saved inputs in fuzz/regressions/TARGET/ and, for the CL targets, ../shared/cl-samples.
# Failing inputs land in build-fuzz/artifacts/TARGET/: copy each into
# fuzz/regressions/TARGET/ with its fix, so ctest replays it for ever (docs/fuzzing.md).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
target=${1:?usage: fuzz/run.sh cl_reader|post|check|script|events [libFuzzer flags]}
shift
case "$target" in cl_reader|post|check|script|events) ;; *) echo "fuzz/run.sh: unknown target '$target'" >&2; exit 2 ;; esac
cxx=${CXX_FUZZ:-clang++-14}
command -v "$cxx" >/dev/null || { echo "fuzz/run.sh: $cxx not found (apt-get install clang-14)" >&2; exit 2; }
bash "$root/scripts/setup.sh"
bin=$root/build-fuzz
cmake -S "$root" -B "$bin" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" -DTWINPOST_FUZZ=ON -DTWINPOST_SANITIZE=address,undefined \
  -DTWINPOST_TESTS=OFF >/dev/null
cmake --build "$bin" -j"$(nproc)" --target "${target}_fuzz"
[ "${FUZZ_BUILD_ONLY:-0}" = 1 ] && exit 0

corpus=$here/corpus/$target
mkdir -p "$corpus" "$bin/artifacts/$target"
cp -n "$here/regressions/$target"/* "$corpus/" 2>/dev/null || true
# Seeds carry a first byte that picks machine and layout (post, check) or dialect (reader).
seed() {  # seed NAME FILE: nine copies, one per first byte 0..8 (events: 18); the reader takes the file as it is
  if [ "$target" = cl_reader ]; then cp "$2" "$corpus/seed-$1"; return; fi
  local ks="0 1 2 3 4 5 6 7 8"
  [ "$target" = events ] && ks="$ks 9 10 11 12 13 14 15 16 17"
  for k in $ks; do { printf "\\$(printf %o "$k")"; cat "$2"; } > "$corpus/seed-$1.$k"; done
}
if [ "$target" = script ]; then
  for f in "$root"/samples/*/*.lua "$root"/samples/post-fail/*/*.lua "$root"/bench/*.lua; do
    seed "$(basename "$(dirname "$f")")-$(basename "$f")" "$f"
  done
elif [ "$target" = events ]; then
  for f in "$here"/seeds/events/*; do seed "$(basename "$f")" "$f"; done
elif [ "$target" = check ]; then
  for f in "$root"/samples/*/expected/*/*; do seed "$(basename "$(dirname "$f")")-$(basename "$f")" "$f"; done
else
  for f in "$root"/samples/*/job.cls; do seed "$(basename "$(dirname "$f")")" "$f"; done
  samples="$root/../shared/cl-samples"
  pieces=$(mktemp -d)  # of this run alone: two targets may be seeded at once
  trap 'rm -rf "$pieces"' EXIT
  if [ -d "$samples" ]; then
    # Pieces of at most 3500 bytes, cut at line ends, so that -max_len=4096 keeps them whole.
    for f in "$samples"/*/*; do
      case "$f" in */README.md) continue ;; esac
      split -C 3500 -d -a 3 "$f" "$pieces/piece-"
      for p in "$pieces"/piece-*; do seed "$(basename "$f").${p##*-}" "$p"; rm "$p"; done
    done
  fi
fi
cd "$here"
if [ "$#" -eq 0 ]; then set -- -runs=1000000; fi
"$bin/${target}_fuzz" -max_len=4096 -artifact_prefix="$bin/artifacts/$target/" -print_final_stats=1 "$@" "$corpus"
