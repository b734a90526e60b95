#!/usr/bin/env bash
# Builds twinpost and its unit tests with ThreadSanitizer into build-tsan/ and runs the tests
# that go through post's second thread (post/concurrent_check.hpp): the unit tests of the
# post and of the streamed reader, and every golden post sample, each of which posts once on
# two threads and once with --threads 1 and holds the two to the same bytes. Any data race
# aborts the test that hit it. .ci/run calls this after the other sanitizers.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DTWINPOST_WERROR=OFF -DTWINPOST_SANITIZE=thread >/dev/null
cmake --build build-tsan -j"$(nproc)" --target twinpost twinpost_tests
export TSAN_OPTIONS=halt_on_error=1:abort_on_error=1:second_deadlock_stack=1
# The pipeline's tests: in-process posts (Catch2 tags of the post tests), the streamed reader,
# and the post samples through the command line.
# Their report is kept, and shown when one fails (a failed assertion goes to standard output,
# which was thrown away: a CI run once stopped here without a word).
if ! ./build-tsan/twinpost_tests "[post],nc_stream_reader*" >build-tsan/unit-tests.log 2>&1; then
  grep -v '^Filters:' build-tsan/unit-tests.log
  echo "tsan.sh: the unit tests under ThreadSanitizer failed (report above)" >&2
  exit 1
fi
ctest --test-dir build-tsan --output-on-failure -j"$(nproc)" -R '^sample\.'
