#!/usr/bin/env python3
"""marsden from Python against the `marsden` command and REBOUND's Python API, in one run.

Each case is timed `--repeats` times; medians and ratios come from the same run (the machines
are shared and noisy: absolute times drift, ratios much less). The figures go to
BENCHMARKS.md.

  - pendulum q0 = 1.5, h = 0.05, 10^6 midpoint steps: `Problem.solve()` against the same
    problem file run by the `marsden` command (process wall time, every 1000th step stored,
    no plots) — the cost of the binding is the difference;
  - Kepler e = 0.6, h = 0.01, 10^6 steps: marsden's midpoint rule from Python, and REBOUND's
    leapfrog (WHFast's kick-drift-kick without the Kepler solver) if `rebound` is installed.

trep (Python 2 only) cannot be installed here: its figures are the peers' figures kept beside the
repository with the C reference (verlet.c).

    python scripts/bench_python.py --marsden target/release/marsden [--repeats 5]
"""

import argparse
import json
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import marsden

STEPS = 1_000_000

PENDULUM = """
[system]
name = "pendulum"
coordinates = ["theta"]
parameters = { m = 1.0, l = 1.0, g = 1.0 }
lagrangian = "0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)"
[initial]
q = [1.5]
v = [0.0]
[integrator]
method = "midpoint"
h = 0.05
steps = 1000000
tolerance = 1e-12
[output]
every = 1000
plots = false
"""

KEPLER = """
[system]
builtin = "kepler"
[initial]
q = [0.4, 0.0]
p = [0.0, 2.0]
[integrator]
method = "midpoint"
h = 0.01
steps = 1000000
tolerance = 1e-14
[output]
every = 1000
plots = false
"""


def median_seconds(run, repeats):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def marsden_pair(binary, text, repeats):
    """Python `solve()` and the command, interleaved (the load of a shared machine drifts):
    medians of the wall times, of the integration times `summary.wall_seconds`, and whether
    the final states agree bit for bit."""
    problem = marsden.Problem.from_toml(text)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "problem.toml"
        path.write_text(text)
        out = Path(tmp) / "out"
        command = [binary, "run", str(path), "--out", str(out)]
        py, cli, py_loop, cli_loop = [], [], [], []
        for _ in range(repeats):
            start = time.perf_counter()
            solution = problem.solve()
            py.append(time.perf_counter() - start)
            py_loop.append(solution.summary["wall_seconds"])
            start = time.perf_counter()
            subprocess.run(command, check=True, capture_output=True)
            cli.append(time.perf_counter() - start)
            summary = json.loads((out / "summary.json").read_text())
            cli_loop.append(summary["wall_seconds"])
    same = solution.summary["final_state"] == summary["final_state"]
    m = statistics.median
    return m(py), m(cli), m(py_loop), m(cli_loop), same


def rebound_kepler(repeats):
    try:
        import rebound
    except ImportError:
        return None

    def run():
        sim = rebound.Simulation()
        sim.G = 1.0
        sim.add(m=1.0)
        sim.add(m=0.0, x=0.4, vy=2.0)
        sim.integrator = "leapfrog"
        sim.dt = 0.01
        sim.steps(STEPS) if hasattr(sim, "steps") else sim.integrate(STEPS * 0.01,
                                                                       exact_finish_time=0)
    return median_seconds(run, repeats)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--marsden", default="target/release/marsden")
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    rows = []
    for name, text in (("pendulum midpoint h=0.05", PENDULUM),
                       ("Kepler e=0.6 midpoint h=0.01", KEPLER)):
        py, cli, py_loop, cli_loop, same = marsden_pair(args.marsden, text, args.repeats)
        rows.append((name, "marsden CLI (process)", cli, 1.0,
                     f"integration {cli_loop:.3f} s"))
        rows.append((name, "marsden Python solve()", py, py / cli,
                     f"integration {py_loop:.3f} s ({py_loop / cli_loop:.2f}x); "
                     + ("final state identical" if same else "FINAL STATE DIFFERS")))
        if name.startswith("Kepler"):
            reb = rebound_kepler(args.repeats)
            if reb is None:
                rows.append((name, "REBOUND leapfrog", float("nan"), float("nan"),
                             "rebound not installed"))
            else:
                rows.append((name, "REBOUND leapfrog (Python API)", reb, reb / cli, ""))
    print(f"{'problem':30} {'tool':32} {'median s':>9} {'ns/step':>8} {'× CLI':>6}  note")
    for name, tool, seconds, ratio, note in rows:
        print(f"{name:30} {tool:32} {seconds:9.3f} {1e9 * seconds / STEPS:8.0f} {ratio:6.2f}  "
              f"{note}")


if __name__ == "__main__":
    main()
