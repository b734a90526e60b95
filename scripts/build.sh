#!/usr/bin/env bash
# Sets up, configures and builds twinpost into build/ (Release, warnings as errors).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DTWINPOST_WERROR=ON >/dev/null
cmake --build build -j"$(nproc)"
