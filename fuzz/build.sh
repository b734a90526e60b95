#!/bin/sh
# Builds and runs the CL reader fuzzer (libFuzzer + ASan + UBSan), one core.
#   fuzz/build.sh            build build-fuzz/cl_reader_fuzz, seed fuzz/corpus/, run 1,000,000 inputs
#   fuzz/build.sh -runs=N    any libFuzzer flags replace the default -runs=1000000
#                            (-max_len=4096 is always passed first; a later -max_len wins)
#   FUZZ_BUILD_ONLY=1 fuzz/build.sh    build only
# The seed corpus is made at run time from ../shared/cl-samples (never committed).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
cxx=${CXX_FUZZ:-clang++-14}
bin="$root/build-fuzz"   # objects, binary and crash artifacts (ignored by git: /build*/)
out="$bin/cl_reader_fuzz"
obj="$bin/obj"
mkdir -p "$obj" "$bin/artifacts"
flags="-std=c++20 -O1 -g -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -I$root"
objs=""
for src in "$root"/parser/*.cpp "$here/cl_reader_fuzz.cpp"; do
  o="$obj/$(basename "$src" .cpp).o"
  if [ ! -f "$o" ] || [ "$src" -nt "$o" ] || [ -n "$(find "$root/parser" -name '*.hpp' -newer "$o" | head -n 1)" ]; then
    echo "compiling $(basename "$src")"
    $cxx $flags -c "$src" -o "$o"
  fi
  objs="$objs $o"
done
# shellcheck disable=SC2086
$cxx -fsanitize=fuzzer,address,undefined $objs -lfmt -o "$out"
echo "built $out"
[ "${FUZZ_BUILD_ONLY:-0}" = 1 ] && exit 0

corpus="$here/corpus"
mkdir -p "$corpus"
samples="$root/../shared/cl-samples"
if [ -d "$samples" ]; then
  # Seeds of at most 3500 bytes, cut at line ends, so that -max_len=4096 keeps them whole.
  for f in "$samples"/*/*; do
    case "$f" in */README.md) continue ;; esac
    split -C 3500 -d -a 3 "$f" "$corpus/seed-$(basename "$f")."
  done
fi
cd "$here"
if [ "$#" -eq 0 ]; then set -- -runs=1000000; fi
set -- -max_len=4096 "$@"
exec "$out" -artifact_prefix="$bin/artifacts/" -print_final_stats=1 "$@" "$corpus"
