#!/usr/bin/env bash
# Quick start 1: set up, build, and post the sample twin-turret job for the Mazak
# Integrex and the Fanuc 2-path lathe; prints the programs and checks them.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
job=samples/shaft-od-drill/job.cls
for machine in integrex-i200st fanuc-0itd-twin; do
  out=out/$machine
  rm -rf "$out"
  echo "== twinpost post $job --machine $machine -o $out"
  ./build/twinpost post "$job" --machine "$machine" -o "$out"
  for f in "$out"/*; do
    echo "---- $f"
    cat "$f"
  done
  echo "== twinpost check $out/* --machine $machine"
  ./build/twinpost check "$out"/* --machine "$machine"
done
