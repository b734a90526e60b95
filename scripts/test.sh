#!/usr/bin/env bash
# Quick start 2: set up, build, and run every test (unit tests and golden samples).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)"
