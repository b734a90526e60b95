#!/usr/bin/env python3
"""Mutation testing of the real command line, as a user meets it.

Takes CL jobs (the samples and ../shared/cl-samples), mutates them (cut at a byte or a line
end, bytes flipped, lines dropped, doubled or swapped, numbers replaced by extreme values,
a record's continuation left dangling) and posts each mutant with `twinpost post` for every
built-in machine and layout, then checks what a user would see:
  - the exit status is 0, 1 or 2, and the run ends within the time limit (no hang);
  - a failed run (status 1 or 2) leaves the output folder as it was (here: absent);
  - a run that succeeds names no file twice, wrote exactly the files it names, and
    `twinpost check` on them exits 0;
  - no '.twinpost-*' temporary folder is left anywhere.
Usage: fuzz/cli_mutate.py TWINPOST [--rounds N] [--seed S]. Exits 1 on the first finding,
with the mutant kept in fuzz-findings/.
"""
import argparse, glob, os, random, re, shutil, subprocess, sys, tempfile

EXTREMES = ["1e308", "-1e308", "1e999", "nan", "inf", "-0", "0", "99999999", "1e-300", "2147483648", "1e", "--1"]


def mutate(text: bytes, rng: random.Random) -> bytes:
    lines = text.split(b"\n")
    kind = rng.randrange(8)
    if kind == 0:  # cut at a byte
        return text[: rng.randrange(len(text) + 1)]
    if kind == 1:  # cut at a line end
        return b"\n".join(lines[: rng.randrange(len(lines) + 1)]) + b"\n"
    if kind == 2:  # flip bytes
        b = bytearray(text)
        for _ in range(rng.randrange(1, 8)):
            if b:
                b[rng.randrange(len(b))] = rng.randrange(256)
        return bytes(b)
    if kind == 3:  # drop a line
        if lines:
            del lines[rng.randrange(len(lines))]
        return b"\n".join(lines)
    if kind == 4:  # double or swap lines
        if len(lines) > 1:
            i, j = rng.randrange(len(lines)), rng.randrange(len(lines))
            if rng.random() < 0.5:
                lines.insert(i, lines[j])
            else:
                lines[i], lines[j] = lines[j], lines[i]
        return b"\n".join(lines)
    if kind == 5:  # an extreme number
        nums = list(re.finditer(rb"-?\d+\.?\d*(?:[eE][-+]?\d+)?", text))
        if nums:
            m = rng.choice(nums)
            return text[: m.start()] + rng.choice(EXTREMES).encode() + text[m.end():]
        return text
    if kind == 6:  # a dangling continuation at the end
        return text.rstrip(b"\n") + b" $\n"
    return text.replace(b"\n", b"\r\n") if rng.random() < 0.5 else text + bytes(rng.randrange(256) for _ in range(20))


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("twinpost")
    ap.add_argument("--rounds", type=int, default=200)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--timeout", type=float, default=20)
    a = ap.parse_args()
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.dirname(here)
    jobs = sorted(glob.glob(os.path.join(root, "samples", "*", "job.cls")))
    jobs += sorted(f for f in glob.glob(os.path.join(root, "..", "shared", "cl-samples", "*", "*")) if not f.endswith(".md"))
    machines = [l.split()[0] for l in subprocess.run([a.twinpost, "machines"], capture_output=True, text=True).stdout.splitlines()]
    layouts = [None, "split", "merged-appended", "merged-sections"]
    rng = random.Random(a.seed)
    counts = {0: 0, 1: 0, 2: 0}
    work = tempfile.mkdtemp(prefix="twinpost-mutate-")
    for r in range(a.rounds):
        src = rng.choice(jobs)
        mutant = mutate(open(src, "rb").read(), rng)
        job = os.path.join(work, "job.cls")
        open(job, "wb").write(mutant)
        machine, layout = rng.choice(machines), rng.choice(layouts)
        out = os.path.join(work, "out")
        shutil.rmtree(out, ignore_errors=True)
        cmd = [a.twinpost, "post", job, "--machine", machine, "-o", out] + (["--layout", layout] if layout else [])

        def finding(what: str) -> int:
            keep = os.path.join(root, "fuzz-findings")
            os.makedirs(keep, exist_ok=True)
            name = os.path.join(keep, f"round{r}.cls")
            open(name, "wb").write(mutant)
            print(f"FINDING round {r}: {what}\n  {' '.join(cmd)}\n  from {src}, kept as {name}")
            return 1

        try:
            p = subprocess.run(cmd, capture_output=True, timeout=a.timeout)
        except subprocess.TimeoutExpired:
            return finding("hang")
        if p.returncode not in (0, 1, 2):
            return finding(f"exit status {p.returncode}: {p.stderr[-400:]!r}")
        counts[p.returncode] += 1
        leftovers = glob.glob(os.path.join(work, "**", ".twinpost-*"), recursive=True)
        if leftovers:
            return finding(f"temporary folder left: {leftovers}")
        if p.returncode != 0:
            if os.path.exists(out):
                return finding(f"failed run left {os.listdir(out)}")
            continue
        wrote = [l.split("wrote ", 1)[1] for l in p.stdout.decode(errors="replace").splitlines() if l.startswith("  wrote ")]
        if len(wrote) != len(set(wrote)):
            return finding(f"two writes to one path: {wrote}")
        if sorted(os.path.join(out, f) for f in os.listdir(out)) != sorted(wrote):
            return finding(f"folder holds {os.listdir(out)}, run named {wrote}")
        c = subprocess.run([a.twinpost, "check", *wrote, "--machine", machine], capture_output=True, timeout=a.timeout)
        if c.returncode != 0:
            return finding(f"check of the posted programs exits {c.returncode}: {c.stdout[-400:]!r}")
    shutil.rmtree(work, ignore_errors=True)
    print(f"{a.rounds} mutants posted: {counts[0]} sound, {counts[1]} input errors, {counts[2]} usage/config errors; no finding")
    return 0


if __name__ == "__main__":
    sys.exit(main())
