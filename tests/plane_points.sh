#!/usr/bin/env bash
# tests/plane_points.sh TWINPOST SOURCE_DIR [SHARED_DIR]: 3+2 output in tilted working planes
# (G68.2) checked by tests/plane_points.py, a reader of its own (LinuxCNC's rs274 reads no
# G68.2): the samples with planes on both 5-axis mills, and the real SolidWorks file
# aamorim_Teste-Metrologia.apt on the trunnion when the shared folder is there. Every GOTO point
# and CIRCLE centre of the CL must come back from the program's plane coordinates. Exit 77
# (skipped) without python3.
set -euo pipefail
twinpost=${1:?usage: plane_points.sh TWINPOST SOURCE_DIR [SHARED_DIR]}
src=${2:?usage: plane_points.sh TWINPOST SOURCE_DIR [SHARED_DIR]}
shared=${TWINPOST_SHARED_DIR:-${3:-$src/../shared}}
command -v python3 >/dev/null || { echo "plane_points.sh: no python3: skipped"; exit 77; }
work=$(mktemp -d "${TMPDIR:-/tmp}/twinpost-plane.XXXXXX")
trap 'rm -rf "$work"' EXIT
check() {  # CL machine
  rm -rf "$work/out"
  "$twinpost" post "$1" --machine "$2" -o "$work/out" >/dev/null
  echo "$(basename "$1") on $2: $(python3 "$src/tests/plane_points.py" "$1" "$work"/out/*.nc)"
}
for m in head-head-5axis trunnion-5axis; do
  check "$src/samples/plane-arc-drill-comp/job.cls" "$m"
  check "$src/samples/three-plus-two/job.cls" "$m"
done
real=$shared/cl-samples/solidworks-cam/aamorim_Teste-Metrologia.apt
if [[ -f $real ]]; then check "$real" trunnion-5axis; else echo "plane_points.sh: no $real: not checked"; fi
