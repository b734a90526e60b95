#!/usr/bin/env bash
# tests/kin_cli.sh TWINPOST SOURCE_DIR: `twinpost kin` end to end on tests/kin/head-head.toml
# (B head over A head, 400 mm from the pivot to the tip of a 100 mm tool, ±20°). Each case
# compares stdout, stderr and the exit status exactly. The joint values of the first case are
# the hand-computed ones of tests/kinematics_inverse_test.cpp: lin = tip + 400·(K - z).
set -uo pipefail
tp=${1:?usage: kin_cli.sh TWINPOST SOURCE_DIR}
src=${2:?usage: kin_cli.sh TWINPOST SOURCE_DIR}
m=$src/tests/kin/head-head.toml
bad=0
expect() {  # expect NAME STATUS STDOUT STDERR -- ARGS...
  local name=$1 status=$2 out=$3 err=$4
  shift 5
  local got_out got_err got_status
  got_out=$("$tp" kin "$@" 2>/tmp/kin_cli_err.$$)
  got_status=$?
  got_err=$(cat /tmp/kin_cli_err.$$)
  rm -f /tmp/kin_cli_err.$$
  if [[ $got_out != "$out" || $got_err != "$err" || $got_status != "$status" ]]; then
    echo "kin_cli.sh: case '$name' differs"
    echo "--- expected (status $status)"; echo "$out"; echo "$err"
    echo "--- got (status $got_status)"; echo "$got_out"; echo "$got_err"
    bad=1
  fi
}

# Vertical; A 10 B 20: 400(K - z) = (134.7296, -69.4593, -29.8334); A 0 B 10 from x -5.
expect "hand values" 0 "1: X10 Y20 Z30 B0 A0
2: X144.7296 Y-49.4593 Z0.1666 B20 A10
3: X64.4593 Y0 Z-6.0769 B10 A0" "" -- \
  --machine "$m" --tool-length 100 10,20,30 10,20,30,0.336824088833465,-0.173648177666930,0.925416578398323 \
  -5,0,0,0.173648177666930,0,0.984807753012208

expect "beyond the limits" 1 "" "twinpost: error: point 1: tool axis (0.5, 0, 0.866) needs B30 A0 (B beyond -20..20) or B-150 A180 (B beyond -20..20; A beyond -20..20)" -- \
  --machine "$m" --tool-length 100 10,20,30,0.5,0,0.8660254

# From B -20 A -20 to B 20 A 20: 31 sub-moves to 0.05 mm, through B 0 A 0 at the middle
# (tip 20,5,0) and symmetric about it.
expect "linearise" 0 "$(cat "$src/tests/kin/linearise.expected")" "" -- \
  --machine "$m" --tool-length 100 --linearise 0.05 \
  0,0,0,-0.321393804843270,0.342020143325669,0.883022221559489 \
  40,10,0,0.321393804843270,-0.342020143325669,0.883022221559489

expect "no chain" 2 "" "twinpost: error: machine 'head-head-test' has no [[kinematics]] for channel 2" -- \
  --machine "$m" --channel 2 1,2,3
expect "bad point" 2 "" "twinpost kin: point '1,2' is not x,y,z or x,y,z,i,j,k" -- --machine "$m" 1,2
expect "bad from" 2 "" "twinpost kin: --from takes 2 rotary value(s), not '1'" -- --machine "$m" --from 1 1,2,3
# The vertical tool has one solution within ±20°, B 0 A 0, wherever the axes come from.
expect "from" 0 "1: X10 Y0 Z0 B0 A0" "" -- --machine "$m" --from 5,-5 10,0,0

# Head/table: the two solutions of one axis, chosen by where the axes come from (the tie from
# 0,0 goes to the positive tilt; from B -10 C 260 the twin is 30° away).
ht=$src/tests/kin/head-table.toml
expect "head/table from 0" 0 "1: X149.3301 Y10 Z-37.6924 B30 C90" "" -- \
  --machine "$ht" --tool-length 50 10,0,5,0,-0.5,0.8660254037844386
expect "head/table from B-10 C260" 0 "1: X-150.6699 Y-10 Z-32.6924 B-30 C270" "" -- \
  --machine "$ht" --tool-length 50 --from -10,260 10,0,5,0,-0.5,0.8660254037844386

if ((bad)); then exit 1; fi
echo "kin_cli.sh: every case as expected"
