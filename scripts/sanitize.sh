#!/usr/bin/env bash
# Builds twinpost with AddressSanitizer and UndefinedBehaviorSanitizer into build-sanitize/
# and runs every test there: unit tests, golden samples, fuzz-corpus replays and (where
# LinuxCNC's rs274 is installed) the oracle. Any finding aborts the test that hit it, so the
# run is green only with zero findings. .ci/run calls this after the README's test command.
#   TWINPOST_SANITIZE=address,undefined   the default list; set it to try another
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
sanitize=${TWINPOST_SANITIZE:-address,undefined}
# -O1 keeps the sanitized binaries quick enough for CI; -g gives the reports their lines.
# Warnings are the release build's to judge: at -O1 with ASan, GCC 12 warns falsely inside
# libstdc++'s <regex> (maybe-uninitialized), so -Werror stays off here.
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DTWINPOST_WERROR=OFF -DTWINPOST_SANITIZE="$sanitize" >/dev/null
cmake --build build-sanitize -j"$(nproc)"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir build-sanitize --output-on-failure -j"$(nproc)"
