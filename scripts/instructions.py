#!/usr/bin/env python3
"""Instructions per step of whole `marsden run` processes, counted by callgrind: the difference
between two runs of the same problem with N1 and N2 steps, divided by N2 − N1 (so parsing,
set-up and writing cancel). Deterministic where wall time on a shared machine is not: the
figure to compare two builds with (BENCHMARKS.md, headline table).

    scripts/instructions.py BIN [BIN2 ...] [--cases k,ke,p,pe,dp,dpe,nb] [--every K]

A case name with `+ev` (`p+ev`, `pe+ev`) adds an event that never fires (`when = "theta - 3"`):
the cost of watching a run for events. `--every K` stores every K-th step (default: none but
the first and the last).

Cases (the headline cases of BENCHMARKS.md): Kepler e = 0.6, h = 0.01, trapezoid (k builtin,
ke as text); pendulum q0 = 1.5, h = 0.05, midpoint (p, pe); double pendulum, h = 0.01,
midpoint (dp, dpe); N-body, Plummer N = 1024, h = 0.001, trapezoid (nb; the data file beside
the repository, ../shared/bench/data).
"""
import argparse
import os
import re
import subprocess
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
PLUMMER = os.path.join(HERE, "../../shared/bench/data/plummer_N1024_seed20241121.txt")
KEPLER = ('coordinates = ["x", "y"]\nparameters = { mu = 1.0 }\n'
          'lagrangian = "0.5*(x_dot^2 + y_dot^2) + mu/sqrt(x^2 + y^2)"')
PENDULUM = ('coordinates = ["theta"]\nparameters = { m = 1.0, l = 1.0, g = 1.0 }\n'
            'lagrangian = "0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)"')
DOUBLE = ('coordinates = ["theta1", "theta2"]\n'
          'parameters = { m1 = 1.0, m2 = 1.0, l1 = 1.0, l2 = 1.0, g = 9.81 }\n'
          'lagrangian = "0.5*(m1 + m2)*l1^2*theta1_dot^2 + 0.5*m2*l2^2*theta2_dot^2'
          ' + m2*l1*l2*theta1_dot*theta2_dot*cos(theta1 - theta2)'
          ' + (m1 + m2)*g*l1*cos(theta1) + m2*g*l2*cos(theta2)"')
DOUBLE_BUILTIN = ('builtin = "double_pendulum"\n'
                  'parameters = { m1 = 1.0, m2 = 1.0, l1 = 1.0, l2 = 1.0, g = 9.81 }')
# name: (system, initial, method, h, (N1, N2))
CASES = {
    "k": ('builtin = "kepler"\nparameters = { mu = 1.0 }', "q = [0.4, 0.0]\np = [0.0, 2.0]",
          "trapezoid", 0.01, (100_000, 300_000)),
    "ke": (KEPLER, "q = [0.4, 0.0]\np = [0.0, 2.0]", "trapezoid", 0.01, (100_000, 300_000)),
    "p": ('builtin = "pendulum"\nparameters = { m = 1.0, l = 1.0, g = 1.0 }',
          "q = [1.5]\np = [0.0]", "midpoint", 0.05, (100_000, 300_000)),
    "pe": (PENDULUM, "q = [1.5]\np = [0.0]", "midpoint", 0.05, (100_000, 300_000)),
    "dp": (DOUBLE_BUILTIN, "q = [1.5, 2.0]\nv = [0.0, 0.0]", "midpoint", 0.01, (10_000, 30_000)),
    "dpe": (DOUBLE, "q = [1.5, 2.0]\nv = [0.0, 0.0]", "midpoint", 0.01, (10_000, 30_000)),
    "nb": ('builtin = "nbody"\nparameters = { G = 1.0, softening = 0.01 }',
           f'file = "{PLUMMER}"', "trapezoid", 0.001, (2, 5)),
}


EVENT = '[[events]]\nname = "never"\nwhen = "theta - 3"\n\n'


def problem(case, steps, out, every):
    base, _, extra = case.partition("+")
    system, initial, method, h, _ = CASES[base]
    event = EVENT if extra == "ev" else ""
    return (f"[system]\n{system}\n\n[initial]\n{initial}\n\n[integrator]\nmethod = \"{method}\"\n"
            f"h = {h}\nsteps = {steps}\ntolerance = 1e-12\n\n{event}[output]\ndir = \"{out}\"\n"
            f"every = {every}\nplots = false\n")


def instructions(binary, case, steps, work, every):
    path = os.path.join(work, f"{case}-{steps}.toml")
    with open(path, "w") as f:
        f.write(problem(case, steps, os.path.join(work, "out"), every))
    run = subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null",
                          binary, "run", path, "--quiet"], capture_output=True, text=True)
    found = re.search(r"Collected : (\d+)", run.stderr)
    if run.returncode != 0 or not found:
        raise SystemExit(f"{binary} run {path} failed:\n{run.stderr[-2000:]}")
    return int(found.group(1))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("binaries", nargs="+")
    ap.add_argument("--cases", default="k,ke,p,pe,dp,dpe,nb")
    ap.add_argument("--every", type=int, default=10_000_000)
    args = ap.parse_args()
    work = tempfile.mkdtemp(prefix="marsden-instructions-")
    cases = args.cases.split(",")
    print("case  " + "  ".join(f"{os.path.basename(os.path.dirname(os.path.dirname(os.path.dirname(b)))) or b:>14}" for b in args.binaries))
    for case in cases:
        n1, n2 = CASES[case.partition("+")[0]][4]
        row = []
        for b in args.binaries:
            counts = [instructions(b, case, n, work, args.every) for n in (n2, n1)]
            per_step = (counts[0] - counts[1]) / (n2 - n1)
            row.append(per_step)
        ratios = "  ".join(f"{r / row[0]:.3f}" for r in row[1:])
        print(f"{case:<5} " + "  ".join(f"{r:>14.1f}" for r in row) + (f"   ratio {ratios}" if ratios else ""), flush=True)


if __name__ == "__main__":
    main()
