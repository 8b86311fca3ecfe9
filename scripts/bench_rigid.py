#!/usr/bin/env python3
"""The heavy top of R20 through `marsden run` beside the hand-written C LGVI
(`verlet.c heavy-top`, kept beside the repository), interleaved repeats, medians.

    scripts/bench_rigid.py BIN [--repeats R] [--steps N] [--verlet PATH_TO_verlet.c]

Cases (h = 0.001, 10^6 steps by default, output stride = the steps, no plots, no progress bar):
  * `builtin = "heavy_top"` (the catalog's entry: the potential `mgl*R33` as an expression);
  * the C LGVI: the same step by hand (Cayley Newton, closed-form moment).
Reported: the integration's wall time per step from summary.json (`wall_seconds / steps`,
parsing and writing excluded) and the C loop's per-step time, with their ratio per repeat pair.
verlet.c is compiled into a temporary directory, never into the repository.
"""
import argparse
import json
import os
import statistics
import subprocess
import tempfile

TOP = """[system]
builtin = "heavy_top"

[initial]
rotation_vector = [0.05, 0.0, 0.0]
Omega = [0.0, 0.0, 50.0]

[integrator]
h = 0.001
steps = {steps}

[output]
dir = "{out}"
every = {steps}
plots = false
"""


def marsden(binary, tmp, steps):
    path = os.path.join(tmp, "top.toml")
    out = os.path.join(tmp, "out")
    with open(path, "w") as f:
        f.write(TOP.format(steps=steps, out=out))
    subprocess.run([binary, "run", path, "--quiet", "--no-progress"], check=True)
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    return s["wall_seconds"] / s["steps"] * 1e9


def c_lgvi(verlet, steps):
    out = subprocess.run([verlet, "heavy-top", "0.001", str(steps), "1"], check=True,
                         capture_output=True, text=True).stdout
    return json.loads(out)["times"][0] / steps * 1e9


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("binary")
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--steps", type=int, default=1_000_000)
    ap.add_argument("--verlet", default=os.path.join(os.path.dirname(__file__), "..", "..",
                                                     "shared", "bench", "verlet.c"))
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        verlet = os.path.join(tmp, "verlet")
        subprocess.run(["gcc", "-O3", "-march=native", args.verlet, "-o", verlet, "-lm"],
                       check=True)
        ours, theirs = [], []
        for _ in range(args.repeats):
            ours.append(marsden(args.binary, tmp, args.steps))
            theirs.append(c_lgvi(verlet, args.steps))
        ratios = [a / b for a, b in zip(ours, theirs)]
        print(f"heavy top, h = 0.001, {args.steps} steps, {args.repeats} interleaved repeats")
        print(f"  marsden run (builtin heavy_top): median {statistics.median(ours):8.1f} ns/step")
        print(f"  C LGVI (verlet.c heavy-top):     median {statistics.median(theirs):8.1f} ns/step")
        print(f"  ratio per pair: median {statistics.median(ratios):.2f}×, "
              f"range {min(ratios):.2f}–{max(ratios):.2f}×")


if __name__ == "__main__":
    main()
