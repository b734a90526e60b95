#!/usr/bin/env python3
"""tests/plane_points.py CL NC [--tol MM]: an independent check of 3+2 output in tilted working
planes (G68.2), which LinuxCNC's rs274 cannot read. It reads the Fanuc program on its own:
G68.2 X Y Z I J K builds the plane's frame from the Z-X-Z Euler angles (Fanuc 30i, "tilted
working plane command": R = Rz(I) Rx(J) Rz(K), origin X Y Z), G69 ends it; every X Y Z the
program reaches is taken back into the part frame (p = origin + R p'), and so is every arc
centre (the start plus I J K, in the plane) and every canned hole (X Y from R to Z along the
plane's Z). Then every GOTO point of the CL file must be found among the points reached, and
every CIRCLE centre among the arc centres, within the tolerance (a hole's point, under CYCLE,
on the line the hole is drilled along). Outside a plane X Y Z are
taken as the tip (tool-tip control, or the rotary axes at 0); with a head machine's joints
output a point written with a tilted head outside a plane cannot be checked here, so the
script counts the CL points it found, and fails on any not found. Exit 0 when all are found.
"""
import math
import re
import sys


def rot(axis, deg, v):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    x, y, z = v
    if axis == "x":
        return (x, c * y - s * z, s * y + c * z)
    return (c * x - s * y, s * x + c * y, z)


def euler_frame(i, j, k):
    turn = lambda v: rot("z", i, rot("x", j, rot("z", k, v)))
    return [turn((1, 0, 0)), turn((0, 1, 0)), turn((0, 0, 1))]


IDENTITY = [(1, 0, 0), (0, 1, 0), (0, 0, 1)]


def to_part(frame, origin, p):
    return tuple(origin[n] + sum(p[m] * frame[m][n] for m in range(3)) for n in range(3))


def words(block):
    return re.findall(r"([A-Z])(-?\d*\.?\d*)", block)


def read_nc(path):
    frame, origin = IDENTITY, (0.0, 0.0, 0.0)
    pos = {"X": None, "Y": None, "Z": None}
    motion = None
    points, centres, holes = [], [], []
    for raw in open(path):
        block = re.sub(r"\(.*?\)", "", raw.strip())
        if not block or block.startswith(("%", "O")):
            continue
        w = words(block)
        gs = [v for a, v in w if a == "G"]
        vals = {a: float(v) for a, v in w if a != "G" and v not in ("", "-", ".")}
        if "68.2" in gs:
            frame = euler_frame(vals.get("I", 0), vals.get("J", 0), vals.get("K", 0))
            origin = (vals.get("X", 0), vals.get("Y", 0), vals.get("Z", 0))
            pos = {"X": None, "Y": None, "Z": None}
            continue
        if "69" in gs:
            frame, origin = IDENTITY, (0.0, 0.0, 0.0)
            pos = {"X": None, "Y": None, "Z": None}
            continue
        if "28" in gs or "53.1" in gs:
            pos = {"X": None, "Y": None, "Z": None}
            continue
        cycle = next((g for g in gs if g in ("81", "82", "83", "73", "84", "74")), None)
        for g in gs:
            if g in ("0", "00", "1", "01", "2", "02", "3", "03"):
                motion = int(float(g))
        start = dict(pos)
        for a in "XYZ":
            if a in vals:
                pos[a] = vals[a]
        if cycle:
            if None not in (pos["X"], pos["Y"]):
                top = to_part(frame, origin, (pos["X"], pos["Y"], vals["R"]))
                bottom = to_part(frame, origin, (pos["X"], pos["Y"], vals["Z"]))
                holes.append((top, bottom))
            pos["Z"] = None  # the cycle ends on the R or initial level
            continue
        if "80" in gs:
            continue
        if None in pos.values() or not any(a in vals for a in "XYZ"):
            continue
        here = to_part(frame, origin, (pos["X"], pos["Y"], pos["Z"]))
        if motion == 1 and None not in start.values():  # an expanded hole's feed, among others
            holes.append((to_part(frame, origin, (start["X"], start["Y"], start["Z"])), here))
        points.append(here)
        if motion in (2, 3) and None not in start.values():
            c = (start["X"] + vals.get("I", 0), start["Y"] + vals.get("J", 0), start["Z"] + vals.get("K", 0))
            centres.append(to_part(frame, origin, c))
    return points, centres, holes


def read_cl(path):
    gotos, circles, drilled = [], [], []
    scale = 1.0
    cycle = False
    text = open(path, errors="replace").read().replace("$\n", "")
    for line in text.splitlines():
        line = line.replace(" ", "").upper()
        if line.startswith("UNIT/IN") or line.startswith("UNITS/INCH"):
            scale = 25.4
        if line.startswith("CYCLE/"):
            cycle = not line.startswith(("CYCLE/OFF", "CYCLE/INIT"))
        if line.startswith(("GOTO/", "CIRCLE/")):
            nums = [float(v) for v in line.split("/", 1)[1].split(",")[:3]]
            point = tuple(scale * v for v in nums)
            (circles if line.startswith("CIRCLE") else drilled if cycle else gotos).append(point)
    return gotos, circles, drilled


def near_segment(p, a, b):
    ab = [b[n] - a[n] for n in range(3)]
    ap = [p[n] - a[n] for n in range(3)]
    ll = sum(v * v for v in ab)
    t = 0 if ll == 0 else max(0.0, min(1.0, sum(ap[n] * ab[n] for n in range(3)) / ll))
    return math.dist(p, [a[n] + t * ab[n] for n in range(3)])


def main():
    args = sys.argv[1:]
    tol = 0.005
    if "--tol" in args:
        i = args.index("--tol")
        tol = float(args[i + 1])
        del args[i : i + 2]
    cl, nc = args
    points, centres, holes = read_nc(nc)
    gotos, circles, drilled = read_cl(cl)
    grid = {}
    for p in points:
        grid.setdefault(tuple(round(v) for v in p), []).append(p)

    def found(q, pts_grid):
        key = tuple(round(v) for v in q)
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for p in pts_grid.get((key[0] + dx, key[1] + dy, key[2] + dz), ()):
                        if math.dist(p, q) <= tol:
                            return True
        return False

    # A hole's point (the CL gives its top) lies on the canned cycle's line or the expanded feed.
    missing = [q for q in gotos if not found(q, grid)]
    missing += [q for q in drilled if not any(near_segment(q, a, b) <= tol for a, b in holes)]
    gotos = gotos + drilled
    # One arc block per CIRCLE: each centre against its own arc's, in order.
    if len(centres) == len(circles):
        lost = [q for q, p in zip(circles, centres) if math.dist(p, q) > tol]
    else:  # full turns (TIMES) or arcs split into blocks: any arc's centre
        cgrid = {}
        for p in centres:
            cgrid.setdefault(tuple(round(v) for v in p), []).append(p)
        lost = [q for q in circles if not found(q, cgrid)]
        print(f"{len(circles)} CIRCLE records in {len(centres)} arc blocks: centres matched as a set")
    print(f"{len(gotos) - len(missing)} of {len(gotos)} GOTO points and {len(circles) - len(lost)} of "
          f"{len(circles)} CIRCLE centres found in the program (tolerance {tol} mm)")
    for q in missing[:5]:
        print(f"  GOTO point not found: {q}")
    for q in lost[:5]:
        print(f"  CIRCLE centre not found: {q}")
    return 1 if missing or lost else 0


if __name__ == "__main__":
    sys.exit(main())
