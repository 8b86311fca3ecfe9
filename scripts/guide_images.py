#!/usr/bin/env python3
"""Redraws the guide's pictures (docs/guide/img/): runs the guide's problem files with the
`marsden` command, keeps the plots the pages show, draws the work–precision plot of "Choosing a
method" from `marsden order`, and quantizes every PNG to 16 colours (each well under 60 KB).

    target/ci-venv/bin/python scripts/guide_images.py            # needs Pillow and matplotlib
    MARSDEN_BIN=target/release/marsden target/ci-venv/bin/python scripts/guide_images.py

The pictures are committed; this script is how they were made (CI does not rerun it: the
numbers behind them are checked by crates/marsden-cli/tests/guide.rs).
"""

from __future__ import annotations

import csv
import os
import pathlib
import subprocess
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from PIL import Image  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "docs" / "guide" / "examples"
IMG = ROOT / "docs" / "guide" / "img"
BIN = os.environ.get("MARSDEN_BIN", str(ROOT / "target" / "release" / "marsden"))

#: (problem file, command, picture the run draws, name in docs/guide/img)
PICTURES = [
    ("pendulum.toml", "run", "phase_portrait.png", "pendulum_phase.png"),
    ("pendulum.toml", "run", "energy_error.png", "pendulum_energy.png"),
    ("central_force.toml", "run", "momentum_drift.png", "central_force_momenta.png"),
    ("discrete_oscillator.toml", "run", "phase_portrait.png", "discrete_oscillator_phase.png"),
    ("kepler.toml", "run", "configuration.png", "kepler_orbit.png"),
    ("kepler.toml", "run", "momentum_drift.png", "kepler_momentum.png"),
    ("exact_oscillator.toml", "run", "energy_error.png", "exact_oscillator_energy.png"),
    ("damped_oscillator.toml", "run", "energy_balance.png", "damped_balance.png"),
    ("spherical_pendulum.toml", "run", "configuration.png", "spherical_configuration.png"),
    ("spherical_pendulum.toml", "run", "constraint_residual.png", "spherical_residual.png"),
    ("spherical_pendulum.toml", "run", "multipliers.png", "spherical_multipliers.png"),
    ("heavy_top.toml", "run", "axis_tip.png", "heavy_top_axis.png"),
    ("free_rigid_body.toml", "run", "body_momentum.png", "free_body_momentum.png"),
    ("pendulum_swing_up.toml", "optimize", "controls.png", "swing_up_controls.png"),
    ("pendulum_swing_up.toml", "optimize", "phase_portrait.png", "swing_up_phase.png"),
    ("sensitivity.toml", "run", "phase_portrait.png", "sensitivity_phase.png"),
    ("henon_heiles_section.toml", "run", "section.png", "henon_heiles_section.png"),
    ("double_pendulum.toml", "run", "time_series.png", "double_pendulum_series.png"),
    ("double_pendulum.toml", "run", "energy_error.png", "double_pendulum_energy.png"),
    ("pendulum_sweep.toml", "run", "sweep.png", "pendulum_sweep.png"),
]

#: The work–precision study: methods and step sizes for `marsden order` on pendulum.toml.
METHODS = "midpoint,trapezoid,gauss-2,lobatto-3,gauss-3,kahan-li-6(trapezoid)"
STEPS = "0.5,0.25,0.125,0.0625,0.03125"


def quantized(source: pathlib.Path, target: pathlib.Path) -> None:
    """Writes `source` to `target` in 16 colours."""
    Image.open(source).convert("RGB").quantize(16).save(target, optimize=True)
    print(f"{target.relative_to(ROOT)}: {target.stat().st_size // 1024} KB")


def run_pictures(tmp: pathlib.Path) -> None:
    done: dict[tuple[str, str], pathlib.Path] = {}
    for file, command, picture, name in PICTURES:
        out = done.get((file, command))
        if out is None:
            out = tmp / f"{command}-{file}"
            subprocess.run([BIN, command, str(EXAMPLES / file), "--out", str(out)],
                           check=True, stdout=subprocess.DEVNULL)
            done[(file, command)] = out
        quantized(out / picture, IMG / name)


def work_precision(tmp: pathlib.Path) -> None:
    """Error at T = 5 against the number of steps, one line per method (R6's problem)."""
    table = tmp / "order.csv"
    subprocess.run([BIN, "order", str(EXAMPLES / "pendulum.toml"), "--methods", METHODS,
                    "--h", STEPS, "--t-end", "5", "--csv", str(table)],
                   check=True, stdout=subprocess.DEVNULL)
    lines: dict[str, list[tuple[int, float]]] = {}
    with open(table) as f:
        for row in csv.DictReader(f):
            lines.setdefault(row["method"], []).append((int(row["steps"]), float(row["error"])))
    fig, ax = plt.subplots(figsize=(6.4, 4.2), dpi=90)
    for method, points in lines.items():
        ax.loglog([n for n, _ in points], [e for _, e in points], "o-", label=method)
    ax.set_xlabel("steps N to T = 5")
    ax.set_ylabel("error |(q_N, p_N) − (q(T), p(T))|")
    ax.set_title("pendulum q0 = 1.5: error against steps")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(tmp / "work_precision.png")
    quantized(tmp / "work_precision.png", IMG / "work_precision.png")


def main() -> None:
    IMG.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        run_pictures(pathlib.Path(tmp))
        work_precision(pathlib.Path(tmp))


if __name__ == "__main__":
    main()
