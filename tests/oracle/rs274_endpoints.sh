#!/usr/bin/env bash
# Oracle: reads a posted program back with LinuxCNC's standalone interpreter and compares
# every move with the CL job it came from.
#
#   rs274_endpoints.sh TWINPOST JOB MACHINE [WORKDIR|-] [post options...]
#
# 1. posts JOB for MACHINE (a built-in name, or a machine TOML file) into WORKDIR/out;
# 2. splits the program per channel (split files by suffix, or merged sections by marker);
# 3. strips what rs274 does not read or what is not motion: waits and other M words, G109,
#    G92 S R / G50 S, T words and M6, G96/G97 S, G94/G95/G98/G99, G4, G28 U0 W0 lines,
#    G40-G42, G54-G59, G49/G67/G69/G80, % and O lines, comments; prefixes G18 G21 G90 G7
#    (G7: X in diameter; G8 for a radius channel; Mazak's G10.9 X1 / X0 are read as G7 / G8)
#    and runs `rs274 -g`;
# 4. takes STRAIGHT_TRAVERSE / STRAIGHT_FEED / ARC_FEED from the canonical output (X as a
#    radius, Z, and for arcs the centre and the sense) and compares them, within 0.001 mm,
#    with the CL moves of the heads that channel serves, from `twinpost parse --json JOB`:
#    GOTO and arc events between HEAD records (HEAD/BOTH copies go to both channels on the
#    head-1 side), X mirrored where the machine mirrors the channel, Z (arc centres and
#    senses with it) reversed while the channel works on a spindle with reverse_z (from its
#    channel.spindle, SPINDL/...,MAIN|SUB, and every channel after TRANSFER/RELEASE), drilling and tapping
#    cycles expanded as the CL's dialect defines them (the oracle's own reading, not the
#    post's: SolidWorks CAM, detected as the post detects it or from --dialect, gives FEDTO as
#    a depth below the hole's top and RTRCTO as the retract plane above it; the others FEDTO
#    as a Z): rapid to the retract plane and to RAPTO above the hole, feed to FEDTO or DEPTH,
#    pecks of STEP (DEEP) with a rapid out to the R plane and back to 0.5 mm above the last
#    depth, or of 1STPECK then SUBPECK (DEEP2) backing off 0.5 mm, rapid out to the retract
#    plane; a tap feeds in and back out to the R plane. Canned cycles in the program (the
#    codes of the machine's [cycles]) are turned into moves here by the oracle's own model of
#    the control before rs274 reads the program: R from the initial level where
#    r_from_initial, else a Z; Q in increments where q_increments; the same 0.5 mm peck
#    clearances (the control's parameters); the return to the initial level; G32 is read as
#    a feed (or as G33, below). Threading and grooving as docs/records.md defines them
#    (CYCLE/THREAD passes at the G76 depths, CYCLE/GROOVE plunges, THREAD/TURN feed moves as
#    synchronised passes). A machine whose [cycles] name a thread or groove cycle rs274 cannot
#    read (G76, G92, G75, Mazak G276/G292) is posted with its thread form set to g32 and its
#    groove form to expanded; the Catch tests (post_thread_test) hold the cycles to that
#    expansion. G32 is read as LinuxCNC's G33 (K = the lead), and each synchronised move must
#    carry the CL's lead. Points that round to the NC words of the previous one (X on the program's
#    0.001 mm grid, in diameter where the channel has it; Z on 0.001 mm) are dropped on both
#    sides (no block is written for them); GOHOME and tool changes write G28, which is stripped, so they are
#    not moves here either.
#
# Exit: 0 all moves agree, 1 a difference (listed), 2 usage or post failure,
#       77 skipped (rs274 or python3 >= 3.11 missing).
set -u

if ! command -v rs274 >/dev/null 2>&1; then
  echo "oracle: rs274 is not installed (apt-get install linuxcnc-uspace); skipped"
  exit 77
fi
if ! command -v python3 >/dev/null 2>&1 || ! python3 -c 'import tomllib' >/dev/null 2>&1; then
  echo "oracle: python3 with tomllib (3.11+) is not available; skipped"
  exit 77
fi
if [ $# -lt 3 ]; then
  echo "usage: rs274_endpoints.sh TWINPOST JOB MACHINE [WORKDIR|-] [post options...]" >&2
  exit 2
fi

here="$(cd "$(dirname "$0")" && pwd)"
exec python3 - "$here" "$@" <<'PYTHON'
import json, math, os, re, shutil, subprocess, sys, tempfile, tomllib

here, twinpost, job, machine = sys.argv[1:5]
rest = sys.argv[5:]
work = rest.pop(0) if rest else "-"
post_args = rest
TOL = 0.001 + 1e-9

def die(code, text):
    print(f"oracle: {text}")
    sys.exit(code)

if work == "-" or work == "":
    work = tempfile.mkdtemp(prefix="twinpost-oracle-")
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)

# --- the machine -----------------------------------------------------------------------
toml_path = machine if machine.endswith(".toml") else os.path.join(here, "..", "..", "machines", "builtin", machine + ".toml")
if not os.path.exists(toml_path):
    die(2, f"no machine file {toml_path}")
with open(toml_path, "rb") as f:
    mdef = tomllib.load(f)
# Spindles whose CL Z runs against the machine's (the sub): the channel's Z sign there.
zsign_of = {sp["name"]: (-1.0 if sp.get("reverse_z", False) else 1.0) for sp in mdef.get("spindle", [])}
channels = []
for ch in mdef.get("channel", []):
    axes = {a["address"]: a for a in ch.get("axis", [])}
    x = axes.get("X")
    channels.append({
        "number": ch["number"],
        "heads": ch.get("heads", []),
        "head_names": [n.upper() for n in ch.get("head_names", [])],
        "suffix": ch.get("file_suffix", ""),
        "diameter": (x.get("diameter", False) if x else True),
        "mirror": bool(x and x.get("mirror", False)),
        "x_min": x.get("min") if x else None,
        "x_max": x.get("max") if x else None,
        "zsign": zsign_of.get(ch.get("spindle", "main"), 1.0),
    })
by_number = {c["number"]: c for c in channels}
cycles = mdef.get("cycles", {})
layout = mdef.get("machine", {}).get("layout", "split")
program = dict(mdef.get("program", {}))
# --layout in the sample's post.args wins over the machine's; merged-sections uses `$n`.
if "--layout" in post_args:
    layout = post_args[post_args.index("--layout") + 1].replace("-", "_")
    if layout == "merged_sections":
        program["section_marker"] = "${channel}"

# --- post and parse --------------------------------------------------------------------
post_machine = machine
cycles = mdef.get("cycles", {})
if cycles.get("thread", "g32") != "g32" or cycles.get("groove", "expanded") != "expanded":
    with open(toml_path, encoding="utf-8") as f:
        text = f.read()
    text = re.sub(r'(?m)^thread = "[^"]*"', 'thread = "g32"', text)
    text = re.sub(r'(?m)^groove = "[^"]*"', 'groove = "expanded"', text)
    post_machine = os.path.join(work, "expanded-cycles.toml")
    with open(post_machine, "w", encoding="utf-8") as f:
        f.write(text)
out_dir = os.path.join(work, "out")
r = subprocess.run([twinpost, "post", job, "--machine", post_machine, "-o", out_dir] + post_args,
                   capture_output=True, text=True)
if r.returncode != 0:
    die(2, f"post failed ({r.returncode}):\n{r.stdout}{r.stderr}")
r = subprocess.run([twinpost, "parse", job, "--json"], capture_output=True, text=True)
if r.returncode != 0:
    die(2, f"parse failed ({r.returncode}):\n{r.stderr}")
events = [json.loads(l) for l in r.stdout.splitlines() if l.strip()]

# --- split the program per channel ------------------------------------------------------
# The programs only: a sample's post.args may ask for the timeline page beside them.
files = sorted(f for f in os.listdir(out_dir) if not f.endswith(".html"))
texts = {}
if layout == "split":
    ext = program.get("extension", "")
    for c in channels:
        want = [f for f in files if f.endswith(c["suffix"] + ext)]
        if len(want) != 1:
            die(1, f"channel {c['number']}: expected one file ending '{c['suffix']}{ext}', found {want}")
        with open(os.path.join(out_dir, want[0]), encoding="latin-1") as f:
            texts[c["number"]] = (want[0], f.read().splitlines())
else:
    if len(files) != 1:
        die(1, f"merged layout: expected one file, found {files}")
    marker = program.get("section_marker", "")
    if "{channel}" not in marker:
        die(2, f"merged layout without a {{channel}} section marker: '{marker}'")
    before, after = marker.replace(" ", "").split("{channel}", 1)
    rx = re.compile("^" + re.escape(before.upper()) + r"(\d+)" + re.escape(after.upper()) + "$")
    current = None
    with open(os.path.join(out_dir, files[0]), encoding="latin-1") as f:
        for line in f.read().splitlines():
            m = rx.match(line.replace(" ", "").upper())
            if m:
                current = int(m.group(1))
                texts.setdefault(current, (files[0], []))
                continue
            if current is not None:
                texts[current][1].append(line)

# --- NC to rs274 -----------------------------------------------------------------------
DROP_BLOCK_G = {4, 10, 28, 50, 53, 92, 109}
KEEP_G = {0, 1, 2, 3, 18, 21, 33, 90}
KEEP_WORDS = set("XYZIKRF")
word_rx = re.compile(r"([A-Z])\s*([-+]?(?:\d+\.?\d*|\.\d+))")

PECK_CLEARANCE = 0.5  # mm: the peck return and chip-break amounts the control is set to

def num(text):
    return float(text)

def canned(codes, words, z_now, out):
    # One canned drilling or tapping block of the machine's [cycles], as moves: the control's
    # behaviour as the oracle models it (docs/machines.md, "[cycles]").
    gs = [v for a, v in codes if a == "G"]
    names = {k: cycles.get(k, "") for k in ("drill_code", "dwell_code", "peck_code", "chip_break_code",
                                           "tap_code", "tap_left_code")}
    mine = [k for k, code in names.items() if code and any(abs(g - float(code[1:])) < 1e-9 for g in gs)]
    if not mine:
        return False
    w = {a: t for a, t in words}
    has = lambda a: a in w
    tap = any(k.startswith("tap") for k in mine)
    x = w.get("X")
    bottom = num(w["Z"])
    r = num(w["R"])
    r_z = z_now + r if cycles.get("r_from_initial", False) else r
    q = num(w["Q"]) / (1000.0 if cycles.get("q_increments", False) else 1.0) if has("Q") else 0.0
    chip = "chip_break_code" in mine and names["chip_break_code"] != names["peck_code"]
    f = w.get("F")
    into = -1.0 if bottom < r_z else 1.0
    if x is not None:
        out.append(f"G0 X{x}")
    out.append(f"G0 Z{r_z:.4f}")
    if q > 0 and not tap:
        depth = r_z + into * q
        while (bottom - depth) * into > 0:
            out.append(f"G1 Z{depth:.4f} F{f}")
            if not chip:
                out.append(f"G0 Z{r_z:.4f}")
            out.append(f"G0 Z{depth - into * PECK_CLEARANCE:.4f}")
            depth += into * q
    out.append(f"G1 Z{bottom:.4f} F{f}")
    if tap:
        out.append(f"G1 Z{r_z:.4f} F{f}")
    out.append(f"G0 Z{z_now:.4f}")  # the return to the initial level
    return True

def clean(lines):
    out = []
    z_now = 0.0
    for raw in lines:
        line = re.sub(r"\([^)]*\)", "", raw.upper()).split(";")[0].strip()
        if not line or line.startswith("%") or re.match(r"^O\d", line):
            continue
        words = word_rx.findall(line)
        codes = [(a, float(v)) for a, v in words]
        if any(a == "M" and int(v) in (2, 30, 99) for a, v in codes):
            break  # the channel's program ends here
        # Mazak G10.9: X in diameter (X1) or radius (X0) from here on, LinuxCNC's G7 and G8.
        if any(a == "G" and abs(v - 10.9) < 1e-9 for a, v in codes):
            x_mode = [v for a, v in codes if a == "X"]
            if x_mode:
                out.append("G7" if x_mode[0] == 1 else "G8")
            continue
        if any(a == "G" and int(round(v)) in DROP_BLOCK_G for a, v in codes):
            continue
        if cycles and canned(codes, words, z_now, out):
            continue
        for a, v in codes:
            if a == "Z":
                z_now = v
        # A motion G-code in a block without axis words (the header's `G0 G90 G54 ...`)
        # would make rs274 move to where it is; twinpost writes G0/G1 on every first move.
        has_axis = any(a in "XYZ" for a, _ in codes)
        sync = any(a == "G" and v == 32 for a, v in codes)  # Fanuc G32 -> LinuxCNC G33 K
        kept = []
        for (a, v), (_, text) in zip(codes, words):
            if sync and a == "G" and v == 32:
                kept.append("G33")
            elif sync and a == "F":
                kept.append("K" + text)
            elif a == "G":
                if not has_axis and v in (0, 1, 2, 3):
                    continue
                if v == int(v) and int(v) in KEEP_G:
                    kept.append(f"G{int(v)}")
            elif a in KEEP_WORDS:
                kept.append(a + text)
        if kept:
            out.append(" ".join(kept))
    return out

ARGS = re.compile(r"\(([^)]*)\)")

def nc_moves(number, lines, diameter):
    ngc = os.path.join(work, f"channel{number}.ngc")
    canon = os.path.join(work, f"channel{number}.canon")
    with open(ngc, "w") as f:
        f.write("G18 G21 G90 " + ("G7" if diameter else "G8") + "\nS100 M3\n")
        f.write("\n".join(clean(lines)) + "\nM2\n")
    # rs274 keeps its tool table in $HOME/.tool.mmap, truncated at start: oracles running
    # side by side (ctest -j) would share it, so each gets its work folder as HOME.
    env = dict(os.environ, HOME=work)
    r = subprocess.run(["rs274", "-g", ngc, canon], capture_output=True, text=True, env=env)
    text = open(canon).read() if os.path.exists(canon) else ""
    moves, errors = [], []
    lead = None
    for l in text.splitlines():
        if "START_SPEED_FEED_SYNC(" in l:
            lead = float(ARGS.search(l).group(1).split(",")[0])
        if "STOP_SPEED_FEED_SYNCH(" in l:
            lead = None
        for kind in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED"):
            if kind + "(" in l:
                v = [float(s) for s in ARGS.search(l).group(1).split(",")]
                if kind == "ARC_FEED":  # XZ plane: first axis Z, second axis X
                    moves.append({"kind": "arc", "x": v[1], "z": v[0], "cx": v[3], "cz": v[2], "ccw": v[4] > 0})
                elif kind == "STRAIGHT_FEED" and lead is not None:
                    moves.append({"kind": f"sync lead {lead:.4f}", "x": v[0], "z": v[2]})
                else:
                    moves.append({"kind": "rapid" if kind == "STRAIGHT_TRAVERSE" else "feed", "x": v[0], "z": v[2]})
    out = (r.stdout + r.stderr).strip().splitlines()
    bad = [l for l in out if l.strip() and l.strip() != "executing"]
    if bad:
        errors = bad
    return moves, errors

# --- CL moves per channel --------------------------------------------------------------
def channel_for_head(h):
    for c in channels:
        if isinstance(h, int) and h in c["heads"]:
            return c["number"]
        if isinstance(h, str) and h.upper() in c["head_names"]:
            return c["number"]
    return None

cl = {c["number"]: [] for c in channels}
first = channel_for_head(1) or 1
active = [(first, -1.0 if by_number[first]["mirror"] else 1.0)]
scale = 1.0
cycle = None

zsign = {c["number"]: c["zsign"] for c in channels}
# A channel whose every move goes through its kinematic chain (the multi-axis mills) comes from
# a tool change as the Fusion posts do: the rotary axes alone, then X Y at the height the tool
# is at, then down (docs/machines.md, "Multi-axis output"): one more rapid, in X at the old Z.
chained = {k.get("channel", 1) for k in mdef.get("kinematics", []) if k.get("moves", "all") == "all"}
approach_due = set()

def emit(move):
    for ch, sign in active:
        m = dict(move)
        zs = zsign[ch]
        m["x"] = sign * move["x"]
        m["z"] = zs * move["z"]
        if "cx" in m:
            m["cx"] = sign * move["cx"]
            m["cz"] = zs * move["cz"]
            # Mirroring X and reversing Z each turn the ZX plane over.
            m["ccw"] = move["ccw"] if sign * zs > 0 else not move["ccw"]
        cl[ch].append(m)

# The CL's dialect, as the post detects it (parser/dialect.cpp), or --dialect.
if "--dialect" in post_args:
    dialect = post_args[post_args.index("--dialect") + 1]
else:
    with open(job, "rb") as f:
        head = f.read(64 * 1024).decode("latin-1")
    if "Pro/CLfile" in head:
        dialect = "creo"
    elif "$$*CATIA0" in head or "CATIA APT" in head:
        dialect = "catia"
    elif "APTCL-SPEC,MAKINO" in head:
        dialect = "makino"
    elif "TOOL PATH/" in head:
        dialect = "nx"
    elif "CSI_SET_" in head or "UNIT/MM" in head or "OPFEATSTART" in head:
        dialect = "solidworks"
    else:
        dialect = "generic"
SOLIDWORKS = dialect == "solidworks"

def expand_cycle(c, x, z, line):
    # Drilling towards -Z (the tool looking down +Z), as the job's dialect defines the words.
    p = dict(c)
    clear = z + p.get("RAPTO", p.get("CLEAR", 0.0)) * scale
    if "FEDTO" in p:
        bottom = z - p["FEDTO"] * scale if SOLIDWORKS else p["FEDTO"] * scale
    elif "DEPTH" in p:
        bottom = z - p["DEPTH"] * scale
    else:
        die(1, f"CL line {line}: cycle without FEDTO or DEPTH")
    initial = z + p["RTRCTO"] * scale if (SOLIDWORKS and "RTRCTO" in p) else clear
    emit({"kind": "rapid", "x": x, "z": initial, "line": line})
    emit({"kind": "rapid", "x": x, "z": clear, "line": line})
    first = later = 0.0
    if c["type"] == "DEEP":
        first = later = p.get("STEP", 0.0) * scale
    elif c["type"] == "DEEP2":
        later = p.get("SUBPECK", 0.0) * scale
        first = p.get("1STPECK", later / scale) * scale
    if c["type"] == "TAP":
        emit({"kind": "feed", "x": x, "z": bottom, "line": line})
        emit({"kind": "feed", "x": x, "z": clear, "line": line})
        emit({"kind": "rapid", "x": x, "z": initial, "line": line})
        return
    depth = clear - first
    while first > 0 and depth > bottom:
        emit({"kind": "feed", "x": x, "z": depth, "line": line})
        if c["type"] == "DEEP":
            emit({"kind": "rapid", "x": x, "z": clear, "line": line})
        emit({"kind": "rapid", "x": x, "z": depth + 0.5, "line": line})
        depth -= later
    emit({"kind": "feed", "x": x, "z": bottom, "line": line})
    emit({"kind": "rapid", "x": x, "z": initial, "line": line})

def expand_thread(c, x0, z0, xr, ze, line):
    # docs/records.md, CYCLE/THREAD: passes at first * sqrt(k) (at least MINCUT more), up to
    # DEPTH - FINISH, then 1 + SPRING passes at DEPTH; each from (x0, z0), flank-shifted.
    p = dict(c)
    starts = int(p.get("STARTS", 1))
    lead = (p["LEAD"] if "LEAD" in p else p["PITCH"] * starts) * scale
    h, fin = p["DEPTH"] * scale, p.get("FINISH", 0.0) * scale
    mincut, angle = p.get("MINCUT", 0.0) * scale, p.get("ANGLE", 0.0)
    taper = p.get("TAPER", 0.0) * scale * (-1.0 if xr < 0 else 1.0)
    rough = h - fin
    first = p["FIRST"] * scale if "FIRST" in p else rough / math.sqrt(p["PASSES"])
    depths, d, k = [], 0.0, 1
    while d < rough - 1e-9:
        d = min(max(first * math.sqrt(k), d + mincut), rough)
        depths.append(d)
        k += 1
    depths += [h] * (1 + int(p.get("SPRING", 0)))
    out = 1.0 if x0 >= xr + taper else -1.0
    along = -1.0 if ze < z0 else 1.0
    tan_a = math.tan(math.radians(angle))
    for s in range(starts):
        zs = z0 - along * s * lead / starts
        if s:
            emit({"kind": "rapid", "x": x0, "z": zs, "line": line})
        for dep in depths:
            zk = zs + along * (dep - depths[0]) * tan_a
            xe = xr + out * (h - dep)
            xs = xe + taper * (ze - zk) / (ze - z0)
            emit({"kind": "rapid", "x": xs, "z": zk, "line": line})
            emit({"kind": f"sync lead {lead:.4f}", "x": xe, "z": ze, "line": line})
            emit({"kind": "rapid", "x": x0, "z": ze, "line": line})
            emit({"kind": "rapid", "x": x0, "z": zs, "line": line})
    if starts > 1:
        emit({"kind": "rapid", "x": x0, "z": z0, "line": line})

def expand_groove(c, x, z, line):
    p = dict(c)
    bottom = p["FEDTO"] * scale if "FEDTO" in p else x - (-1.0 if x < 0 else 1.0) * p["DEPTH"] * scale
    into = -1.0 if bottom < x else 1.0
    clear = x - into * p["RAPTO"] * scale
    width, step = p.get("WIDTH", 0.0) * scale, p.get("ZSTEP", 0.0) * scale
    sign = -1.0 if width < 0 else 1.0
    zend = z - sign * abs(width)
    zi = z
    emit({"kind": "rapid", "x": clear, "z": z, "line": line})
    while True:
        last = (zi - zend) * sign <= 1e-9
        if last:
            zi = zend
        emit({"kind": "rapid", "x": clear, "z": zi, "line": line})
        emit({"kind": "feed", "x": bottom, "z": zi, "line": line})
        emit({"kind": "rapid", "x": clear, "z": zi, "line": line})
        if last:
            break
        zi -= sign * step
    emit({"kind": "rapid", "x": clear, "z": z, "line": line})
    return clear, z

pos = (0.0, 0.0)
thread_lead = None
for e in events:
    kind, line = e.get("event"), e.get("line")
    if kind == "units":
        scale = 25.4 if e.get("units") == "inch" else 1.0
    elif kind == "head":
        h = e.get("head")
        if h == "BOTH":
            a, b = channel_for_head(1), channel_for_head(2)
            active = [(a, 1.0), (b, 1.0)]
        else:
            n = channel_for_head(h)
            if n is None:
                die(2, f"CL line {line}: no channel for head {h}")
            active = [(n, -1.0 if by_number[n]["mirror"] else 1.0)]
    elif kind == "channel":
        n = int(e["channel"])
        active = [(n, -1.0 if by_number[n]["mirror"] else 1.0)]
    elif kind == "spindle" and e.get("spindle") in ("main", "sub"):
        for ch, _ in active:
            zsign[ch] = zsign_of.get(e["spindle"], 1.0)
    elif kind == "transfer" and e.get("step") == "release":
        for ch in zsign:
            zsign[ch] = zsign_of.get("sub", 1.0)
    elif kind == "tool" and not e.get("preselect"):
        approach_due.update(ch for ch, _ in active if ch in chained)
    elif kind == "cycle":
        cycle = None if e.get("type") in ("OFF", "ON", "INIT") else e
    elif kind == "thread":
        thread_lead = e.get("lead") * scale if e.get("mode") == "TURN" else None
    elif kind in ("goto", "godlta"):
        x, z = e["x"] * scale, e["z"] * scale
        for ch, sign in active:
            # A hole as the first move (NX's CYCLE before the first GOTO) is approached the same way.
            if ch in approach_due and (e.get("rapid") or (cycle and cycle["type"] not in ("THREAD", "GROOVE"))):
                last_z = cl[ch][-1]["z"] if cl[ch] else 0.0  # where the last move left the tool
                cl[ch].append({"kind": "rapid", "x": sign * x, "z": last_z, "line": line})
            approach_due.discard(ch)
        if cycle and cycle["type"] == "THREAD":
            expand_thread(cycle, pos[0], pos[1], x, z, line)
            continue  # the cycle ends where it started
        elif cycle and cycle["type"] == "GROOVE":
            pos = expand_groove(cycle, x, z, line)
            continue
        elif cycle:
            expand_cycle(cycle, x, z, line)
        elif thread_lead and not e.get("rapid"):
            emit({"kind": f"sync lead {thread_lead:.4f}", "x": x, "z": z, "line": line})
        else:
            emit({"kind": "rapid" if e.get("rapid") else "feed", "x": x, "z": z, "line": line})
        pos = (x, z)
    elif kind == "arc":
        ccw_about_y = (e["dir"] == "ccw") == (e["j"] > 0)
        emit({"kind": "arc", "x": e["x"] * scale, "z": e["z"] * scale, "cx": e["cx"] * scale,
              "cz": e["cz"] * scale, "ccw": ccw_about_y, "line": line})

def dedupe(moves, diameter):
    # A point that rounds to the same NC words as the one before it writes no block: X on the
    # 0.001 mm grid of the program (a diameter on diameter channels), Z on 0.001 mm.
    out, last = [], None
    for m in moves:
        here_ = (round(m["x"] * (2000 if diameter else 1000)), round(m["z"] * 1000))
        if m["kind"] != "arc" and here_ == last:
            continue
        out.append(m)
        last = here_
    return out

def show(m):
    s = f"{m['kind']} X(radius) {m['x']:.3f} Z {m['z']:.3f}"
    if m["kind"] == "arc":
        s += f" centre {m['cx']:.3f},{m['cz']:.3f} {'ccw' if m['ccw'] else 'cw'} about +Y"
    return s

# --- compare ---------------------------------------------------------------------------
name = os.path.basename(os.path.dirname(os.path.abspath(job))) or job
failed = False
for c in channels:
    n = c["number"]
    fname, lines = texts.get(n, ("<none>", []))
    nc, errors = nc_moves(n, lines, c["diameter"])
    nc, want = dedupe(nc, c["diameter"]), dedupe(cl[n], c["diameter"])
    problems = [f"rs274: {l}" for l in errors]
    for i in range(max(len(nc), len(want))):
        if i >= len(nc):
            problems.append(f"move {i + 1}: CL line {want[i].get('line')} {show(want[i])}: no NC move")
            continue
        if i >= len(want):
            problems.append(f"move {i + 1}: NC {show(nc[i])}: no CL move")
            continue
        a, b = nc[i], want[i]
        same = a["kind"] == b["kind"] and abs(a["x"] - b["x"]) <= TOL and abs(a["z"] - b["z"]) <= TOL
        if same and a["kind"] == "arc":
            same = abs(a["cx"] - b["cx"]) <= TOL and abs(a["cz"] - b["cz"]) <= TOL and a["ccw"] == b["ccw"]
        if not same:
            problems.append(f"move {i + 1}: CL line {b.get('line')} {show(b)}; NC {show(a)}")
    # X is measured from the spindle centre, so the channel's X travel applies as written
    # (Z is not checked: the program's Z is relative to a work offset).
    factor = 2.0 if c["diameter"] else 1.0
    for i, m in enumerate(nc):
        x = m["x"] * factor
        if (c["x_min"] is not None and x < c["x_min"] - TOL) or (c["x_max"] is not None and x > c["x_max"] + TOL):
            problems.append(f"move {i + 1}: NC X{x:.3f} is outside the channel's X travel {c['x_min']}..{c['x_max']}")
    problems = problems[:12]
    if problems:
        failed = True
        print(f"oracle: {name} on {machine}: channel {n} ({fname}): {len(problems)} problem(s)", flush=True)
        for p in problems:
            print(f"  {p}")
    else:
        print(f"oracle: {name} on {machine}: channel {n} ({fname}): {len(nc)} moves agree with the CL")
print(f"oracle: work files in {work}")
sys.exit(1 if failed else 0)
PYTHON
