#!/usr/bin/env bash
# Oracle: twinpost's inverse kinematics against LinuxCNC's own kinematics modules.
#
#   kins_oracle.sh TWINPOST SOURCE_DIR CHAIN WORKDIR
#
# CHAIN is trt (xyzac-trt-kins: an A tilting table carrying a C table, trt.ini/.hal/.toml)
# or bridge (5axiskins: a C head carrying a B head, 250 mm from the B pivot to the tip,
# bridge.ini/.hal/.toml). For a fixed list of 16 poses (tips and rotary angles spread over
# the range, tilts up to 110 degrees of both signs, C past 180 and below 0):
#
# 1. the tool axis K of each pose on the part, from LinuxCNC's description of the chain
#    (trt.toml and bridge.toml say where each formula comes from);
# 2. LinuxCNC itself, headless (a copy of this folder in WORKDIR; DISPLAY = drive.py), moves
#    to each pose with MDI `G0 X Y Z <angles>` (X Y Z: the tip on the part, the world
#    coordinates of both modules) and reports the joints its module's inverse commands;
#    a second move per pose probes K with LinuxCNC's own geometry: on the trunnion the tip
#    moved by 10·K on the part must move only the Z joint, by 10 (the tool is along machine
#    Z); on the bridge mill W10 (5axiskins moves W along the tool) must move X Y Z by 10·K;
# 3. `twinpost kin` on the same machine as a twinpost machine file solves the CL poses
#    (tip, K), as one path from rotaries at 0 (each point from the one before);
# 4. twinpost's X Y Z and rotary values must equal LinuxCNC's joints within 0.001 mm and
#    0.001 degrees (twinpost prints 4 decimals). The poses follow a path on which the
#    nearest of the two solutions is the one LinuxCNC was given (by at least 10 degrees of
#    total rotary move); when twinpost takes the other, the message says so.
#
# LinuxCNC needs a non-root uid for its realtime process when run as root (RTAPI_UID), and
# only one LinuxCNC may run on a machine: runs of this script are serialised by flock, and it
# will not start beside a LinuxCNC it did not start (/tmp/linuxcnc.lock). Every process it
# starts is stopped on exit (the `linuxcnc` script's own clean-up, then its process group,
# then `halrun -U`).
#
# Exit: 0 all agree, 1 a difference (listed), 2 usage or a failed run, 77 skipped
#       (LinuxCNC, its Python module or python3 missing, or another LinuxCNC running).
set -u

skip() { echo "oracle: $*; skipped"; exit 77; }

if [ $# -ne 4 ]; then
  echo "usage: kins_oracle.sh TWINPOST SOURCE_DIR trt|bridge WORKDIR" >&2
  exit 2
fi
twinpost=$1 src=$2 chain=$3 work=$4
case $chain in
  trt) kins=xyzac-trt-kins ;;
  bridge) kins=5axiskins ;;
  *) echo "kins_oracle.sh: chain '$chain' is not trt or bridge" >&2; exit 2 ;;
esac
here=$src/tests/oracle/linuxcnc

command -v linuxcnc >/dev/null 2>&1 || skip "LinuxCNC is not installed (apt-get install linuxcnc-uspace)"
command -v halrun >/dev/null 2>&1 || skip "LinuxCNC's halrun is not installed"
[ -e "/usr/lib/linuxcnc/modules/$kins.so" ] || skip "LinuxCNC has no $kins module (/usr/lib/linuxcnc/modules/$kins.so)"
/usr/bin/python3 -c 'import linuxcnc' >/dev/null 2>&1 || skip "/usr/bin/python3 cannot import LinuxCNC's linuxcnc module"
command -v python3 >/dev/null 2>&1 || skip "python3 is not available"
command -v flock >/dev/null 2>&1 || skip "flock (util-linux) is not available"

rm -rf "$work"
mkdir -p "$work" || exit 2
cp -p "$here/drive.py" "$here/$chain.ini" "$here/$chain.hal" "$here/oracle.tbl" "$work/" || exit 2

# One LinuxCNC at a time on this machine (a lock file of another user's that this one may
# not write: then only the check of /tmp/linuxcnc.lock below).
lock=/tmp/twinpost-linuxcnc-oracle.lock
[ -e "$lock" ] && [ ! -w "$lock" ] && lock=$work/oracle.lock
exec 9>>"$lock"
chmod a+rw "$lock" 2>/dev/null
flock -w 120 9 || skip "another run of this oracle held its lock for 2 minutes"
[ -e /tmp/linuxcnc.lock ] && skip "another LinuxCNC is running (/tmp/linuxcnc.lock): not started beside it"

# The realtime process (a non-root uid under root) makes its socket here: a folder of its own
# in /tmp, which that uid can reach whatever the work folder's parents allow (a checkout in a
# `mktemp -d` folder is 0700).
rt=$(mktemp -d /tmp/twinpost-lcnc-rt.XXXXXX) || exit 2
chmod 1777 "$rt"
export RTAPI_FIFO_PATH=$rt/fifo HOME=$work
unset DISPLAY
if [ "$(id -u)" = 0 ]; then
  export RTAPI_UID=${RTAPI_UID:-$(id -u nobody 2>/dev/null || echo 65534)}
fi

lcnc_pid= lcnc_group=
cleanup() {
  if [ -n "$lcnc_pid" ] && kill -0 "$lcnc_pid" 2>/dev/null; then
    kill -TERM "$lcnc_pid" 2>/dev/null  # the linuxcnc script's trap runs its Cleanup
    for _ in $(seq 50); do kill -0 "$lcnc_pid" 2>/dev/null || break; sleep 0.2; done
    kill -KILL -- "-$lcnc_pid" 2>/dev/null
    halrun -U >/dev/null 2>&1
    rm -f /tmp/linuxcnc.lock
  fi
  # Whatever of the group is still there (nothing, after a normal run).
  [ -n "$lcnc_group" ] && kill -KILL -- "-$lcnc_group" 2>/dev/null
  lcnc_pid= lcnc_group=
  rm -rf "$rt"
}
trap cleanup EXIT
trap 'cleanup; exit 2' INT TERM

# Poses, moves.txt and the CL points (python prints the points, one per line, to points.txt).
python3 - "$chain" "$work" <<'PYTHON' || exit 2
import math, sys
chain, work = sys.argv[1:3]
# (tip x, y, z, angles): A C on the trunnion, B C on the bridge mill; a path on which the
# nearest solution from the point before is the one listed.
POSES = {
    "trt": [((0, 0, 0), (0, 0)), ((25, -10, 5), (15, 30)), ((40, 10, -20), (35, 75)),
            ((-30, 45, 10), (60, 140)), ((-50, -20, 30), (85, 200)), ((10, -60, -5), (45, 265)),
            ((60, 30, 15), (20, 330)), ((5, 5, 40), (-10, 350)), ((-20, 35, -15), (-40, 300)),
            ((45, -40, 25), (-75, 220)), ((-60, -5, -30), (-55, 150)), ((15, 50, 0), (-25, 60)),
            ((30, -25, -40), (-5, -20)), ((-35, 15, 20), (30, -45)), ((0, 0, 0), (-90, -100)),
            ((20, -20, 10), (-110, -150))],
    "bridge": [((0, 0, 0), (0, 0)), ((10, 20, -5), (20, 0)), ((30, -15, 10), (45, 30)),
               ((-25, 40, 0), (-30, 60)), ((50, 5, -20), (-60, 110)), ((-40, -30, 15), (-85, 170)),
               ((15, 60, -10), (-50, 250)), ((0, -50, 30), (-15, 330)), ((35, 25, -35), (10, 350)),
               ((-55, 10, 5), (40, 300)), ((20, -45, 20), (70, 230)), ((-10, 30, -25), (95, 180)),
               ((45, -5, 0), (55, 100)), ((-30, -35, 35), (25, -10)), ((5, 15, -40), (-35, -60)),
               ((0, 0, 0), (-110, -135))],
}
rad = math.radians
moves, points, expected = [], [], []
for tip, (r1, r2) in POSES[chain]:
    if chain == "trt":
        a, c = rad(r1), rad(r2)
        # LinuxCNC manual, xyzac-trt with rotary axis offsets, eq. (22).
        k = (math.sin(c) * math.sin(a), math.cos(c) * math.sin(a), math.cos(a))
        moves.append("G0 X%.12f Y%.12f Z%.12f A%.12f C%.12f" % (*tip, r1, r2))
        moves.append("G0 X%.12f Y%.12f Z%.12f" % tuple(t + 10 * q for t, q in zip(tip, k)))
    else:
        b, c = rad(r1), rad(r2)
        # 5axiskins as bridge.toml describes it (the W probe checks it).
        k = (-math.sin(b) * math.cos(c), -math.sin(b) * math.sin(c), math.cos(b))
        moves.append("G0 X%.12f Y%.12f Z%.12f B%.12f C%.12f W0" % (*tip, r1, r2))
        moves.append("G0 W10")
    points.append(",".join("%.15f" % v for v in (*tip, *k)))
    expected.append(" ".join(repr(float(v)) for v in (*tip, *k, r1, r2)))
with open(f"{work}/moves.txt", "w") as f:
    f.write("\n".join(moves) + "\n")
with open(f"{work}/points.txt", "w") as f:
    f.write("\n".join(points) + "\n")
with open(f"{work}/poses.txt", "w") as f:
    f.write("\n".join(expected) + "\n")
PYTHON

# LinuxCNC, in its own process group (setsid) so that everything it starts can be stopped.
setsid linuxcnc "$work/$chain.ini" >"$work/linuxcnc.log" 2>&1 </dev/null &
lcnc_pid=$! lcnc_group=$!
for _ in $(seq 300); do kill -0 "$lcnc_pid" 2>/dev/null || break; sleep 0.1; done
if kill -0 "$lcnc_pid" 2>/dev/null; then
  echo "oracle: LinuxCNC did not finish within 30 s (log: $work/linuxcnc.log)"
  exit 2
fi
wait "$lcnc_pid"
lcnc_status=$?
lcnc_pid=
if [ ! -s "$work/joints.txt" ]; then
  echo "oracle: LinuxCNC wrote no joints (exit $lcnc_status); its logs:"
  # The `linuxcnc` script leaves its print and debug files in $HOME (here: $work) on failure.
  for f in "$work/linuxcnc.log" "$work/linuxcnc_print.txt" "$work/linuxcnc_debug.txt"; do
    [ -s "$f" ] && { echo "--- $f"; tail -n 20 "$f"; }
  done
  exit 2
fi

tool=()
[ "$chain" = bridge ] && tool=(--tool-length 100)
mapfile -t points <"$work/points.txt"
"$twinpost" kin --machine "$here/$chain.toml" "${tool[@]}" "${points[@]}" >"$work/twinpost.txt" 2>"$work/twinpost.err"
tp_status=$?

python3 - "$chain" "$work" "$tp_status" <<'PYTHON'
import math, re, sys
chain, work, tp_status = sys.argv[1], sys.argv[2], int(sys.argv[3])
TOL_MM, TOL_DEG = 0.001, 0.001
rot = ("A", "C") if chain == "trt" else ("B", "C")
poses = [[float(v) for v in l.split()] for l in open(f"{work}/poses.txt") if l.strip()]
joints = {}
for l in open(f"{work}/joints.txt"):
    n, rest = l.split(None, 1)
    joints[int(n)] = rest.strip()
problems = []
if tp_status != 0:
    print(f"oracle: twinpost kin failed ({tp_status}): {open(work + '/twinpost.err').read().strip()}")
    sys.exit(1)
tp = {}
for l in open(f"{work}/twinpost.txt"):
    m = re.match(r"^(\d+): (.*)$", l.strip())
    if m:
        tp[int(m.group(1))] = {w[0]: float(w[1:]) for w in m.group(2).split()}
worst = [0.0, 0.0, 0.0]  # twinpost-LinuxCNC mm, degrees; the probe's departure from K
for i, pose in enumerate(poses, 1):
    tip, k, ang = pose[0:3], pose[3:6], pose[6:8]
    move, probe = joints.get(2 * i - 1, "missing"), joints.get(2 * i, "missing")
    if "ERROR" in move or "ERROR" in probe or move == "missing" or probe == "missing":
        problems.append(f"pose {i}: LinuxCNC: {move} / {probe}")
        continue
    j = [float(v) for v in move.split()]
    p = [float(v) for v in probe.split()]
    if any(abs(j[3 + n] - ang[n]) > 1e-9 for n in range(2)):
        problems.append(f"pose {i}: LinuxCNC's rotary joints {j[3:5]} are not the angles commanded {ang}")
    # The probe: the joints' move must be 10 along the tool, K on the part.
    want = [0.0, 0.0, 10.0] if chain == "trt" else [10 * q for q in k]
    off = max(abs(p[n] - j[n] - want[n]) for n in range(3))
    worst[2] = max(worst[2], off)
    if off > 1e-6:
        problems.append(f"pose {i}: LinuxCNC's own tool axis is not K = {k}: the probe moved the joints by "
                        f"{[round(p[n] - j[n], 6) for n in range(3)]}, not {want}")
    t = tp.get(i)
    if t is None:
        problems.append(f"pose {i}: twinpost printed no point {i}")
        continue
    lin = [t["X"], t["Y"], t["Z"]]
    tr = [t[rot[0]], t[rot[1]]]
    dl = max(abs(lin[n] - j[n]) for n in range(3))
    dr = max(abs(tr[n] - j[3 + n]) for n in range(2))
    worst[0], worst[1] = max(worst[0], dl), max(worst[1], dr)
    if dl > TOL_MM + 1e-9 or dr > TOL_DEG + 1e-9:
        twin = (abs(tr[0] + ang[0]) < TOL_DEG and abs(math.remainder(tr[1] - ang[1] - 180.0, 360.0)) < TOL_DEG)
        turn = (abs(tr[0] - ang[0]) < TOL_DEG and abs(math.remainder(tr[1] - ang[1], 360.0)) < TOL_DEG)
        why = (" (the same angles: the positions differ)" if dr <= TOL_DEG + 1e-9 else
               " (twinpost took the other solution of this tool axis)" if twin else
               " (the same angles a whole turn apart)" if turn else "")
        problems.append(f"pose {i}: tip {tip} K ({k[0]:.6f}, {k[1]:.6f}, {k[2]:.6f}): "
                        f"LinuxCNC X{j[0]:.4f} Y{j[1]:.4f} Z{j[2]:.4f} {rot[0]}{j[3]:g} {rot[1]}{j[4]:g}, "
                        f"twinpost X{lin[0]:.4f} Y{lin[1]:.4f} Z{lin[2]:.4f} {rot[0]}{tr[0]:g} {rot[1]}{tr[1]:g}{why}")
name = {"trt": "xyzac-trt-kins (trt.toml)", "bridge": "5axiskins (bridge.toml)"}[chain]
if problems:
    print(f"oracle: {name}: {len(problems)} problem(s)")
    for p in problems[:20]:
        print(f"  {p}")
    print(f"oracle: work files in {work}")
    sys.exit(1)
print(f"oracle: {name}: {len(poses)} poses, twinpost kin = LinuxCNC's joints within {TOL_MM} mm and "
      f"{TOL_DEG} degrees (largest difference {worst[0]:.5f} mm, {worst[1]:.5f} degrees; "
      f"LinuxCNC's tool axis = K within {worst[2]:.1e} mm over 10 mm)")
PYTHON
