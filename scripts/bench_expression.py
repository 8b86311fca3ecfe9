#!/usr/bin/env python3
"""A Lagrangian typed as text against the same system from the catalog, through `marsden run`,
with the C references (verlet.c, kept beside the repository), all in one run (interleaved
repeats, medians).

    scripts/bench_expression.py NEW_BIN [OLD_BIN] [--repeats R] [--verlet PATH_TO_verlet.c]

Cases (output stride 10^7, no plots, progress bar off):
  * Kepler e = 0.6, h = 0.01, trapezoid, 10^7 steps: builtin, expression; C velocity Verlet;
  * pendulum q0 = 1.5, h = 0.05, midpoint, 10^7 steps: builtin, expression; C Newton for the
    same map (`verlet pendulum-midpoint`);
  * double pendulum, h = 0.01, midpoint, 10^6 steps: builtin, expression.
Times are the wall time of the whole process (parsing, setup, run, writing). With OLD_BIN, each
case also runs with it (before/after in the same run). verlet.c is compiled into a temporary
directory, never into the repository.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

KEPLER_TEXT = "0.5*(x_dot^2 + y_dot^2) + mu/sqrt(x^2 + y^2)"
PENDULUM_TEXT = "0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)"
DOUBLE_TEXT = ("0.5*(m1 + m2)*l1^2*theta1_dot^2 + 0.5*m2*l2^2*theta2_dot^2"
               " + m2*l1*l2*theta1_dot*theta2_dot*cos(theta1 - theta2)"
               " + (m1 + m2)*g*l1*cos(theta1) + m2*g*l2*cos(theta2)")

SYSTEMS = {
    "kepler": ('builtin = "kepler"\nparameters = { mu = 1.0 }',
               f'coordinates = ["x", "y"]\nparameters = {{ mu = 1.0 }}\nlagrangian = "{KEPLER_TEXT}"',
               "q = [0.4, 0.0]\np = [0.0, 2.0]", "trapezoid", 0.01, 10_000_000),
    "pendulum": ('builtin = "pendulum"\nparameters = { m = 1.0, l = 1.0, g = 1.0 }',
                 'coordinates = ["theta"]\nparameters = { m = 1.0, l = 1.0, g = 1.0 }\n'
                 f'lagrangian = "{PENDULUM_TEXT}"',
                 "q = [1.5]\np = [0.0]", "midpoint", 0.05, 10_000_000),
    "double_pendulum": ('builtin = "double_pendulum"\n'
                        'parameters = { m1 = 1.0, m2 = 1.0, l1 = 1.0, l2 = 1.0, g = 9.81 }',
                        'coordinates = ["theta1", "theta2"]\n'
                        'parameters = { m1 = 1.0, m2 = 1.0, l1 = 1.0, l2 = 1.0, g = 9.81 }\n'
                        f'lagrangian = "{DOUBLE_TEXT}"',
                        "q = [1.5, 2.0]\nv = [0.0, 0.0]", "midpoint", 0.01, 1_000_000),
}


def problem(system, initial, method, h, steps, out):
    return (f"[system]\n{system}\n\n[initial]\n{initial}\n\n[integrator]\nmethod = \"{method}\"\n"
            f"h = {h}\nsteps = {steps}\ntolerance = 1e-12\n\n[output]\ndir = \"{out}\"\n"
            "every = 10000000\nplots = false\n")


def timed(cmd):
    start = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - start


def verlet_run(binary, mode, h, steps):
    out = subprocess.run([binary, mode, str(h), str(steps), "1"], check=True,
                         capture_output=True, text=True).stdout
    record = json.loads(out)
    times = record.get("times") or record.get("wall") or []
    return min(times) if times else float("nan")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("new")
    ap.add_argument("old", nargs="?")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--verlet", default=os.path.join(os.path.dirname(__file__),
                                                      "../../shared/bench/verlet.c"))
    args = ap.parse_args()
    work = tempfile.mkdtemp(prefix="marsden-bench-expr-")
    verlet = os.path.join(work, "verlet")
    subprocess.run(["gcc", "-O3", "-march=native", args.verlet, "-o", verlet, "-lm"], check=True)
    bins = {"new": args.new} | ({"old": args.old} if args.old else {})
    files = {}
    for name, (builtin, expr, initial, method, h, steps) in SYSTEMS.items():
        for kind, system in (("builtin", builtin), ("expression", expr)):
            path = os.path.join(work, f"{name}-{kind}.toml")
            with open(path, "w") as f:
                f.write(problem(system, initial, method, h, steps, os.path.join(work, "out")))
            files[(name, kind)] = path
    times = {}
    c_modes = {"kepler": ("kepler", 0.01, 10_000_000),
               "pendulum": ("pendulum-midpoint", 0.05, 10_000_000)}
    for r in range(args.repeats):
        for name, (mode, h, steps) in c_modes.items():
            times.setdefault((name, "C"), []).append(verlet_run(verlet, mode, h, steps))
        for (name, kind), path in files.items():
            for tag, binary in bins.items():
                t = timed([binary, "run", path, "--quiet", "--no-progress"])
                times.setdefault((name, f"{kind} ({tag})"), []).append(t)
        print(f"repeat {r + 1}/{args.repeats} done", file=sys.stderr)
    med = {k: statistics.median(v) for k, v in times.items()}
    print("| system | variant | ns/step | × builtin (same binary) | × C |")
    print("|---|---|---|---|---|")
    for name, (_, _, _, _, _, steps) in SYSTEMS.items():
        c = med.get((name, "C"))
        if c:
            print(f"| {name} | C reference | {c / steps * 1e9:.1f} | | 1 |")
        for tag in bins:
            base = med[(name, f"builtin ({tag})")]
            for kind in ("builtin", "expression"):
                t = med[(name, f"{kind} ({tag})")]
                xc = f"{t / c:.2f}" if c else ""
                print(f"| {name} | {kind} ({tag}) | {t / steps * 1e9:.1f} | {t / base:.2f} | {xc} |")


if __name__ == "__main__":
    main()
