"""Jointed rigid bodies from Python: ``Problem.from_toml`` on ``examples/pendulum_3d.toml`` (the
3D pendulum of reference case R22: the vertical angular momentum about the pivot to round-off),
``Solution.bodies`` by name, the same bits as ``marsden run``, and a bad joint as
``ProblemError``."""

from __future__ import annotations

import json
import subprocess

import numpy as np
import pytest

import marsden
from conftest import EXAMPLES


def pendulum_3d(steps: int = 1000) -> marsden.Solution:
    text = (EXAMPLES / "pendulum_3d.toml").read_text().replace("t_end = 20.0", f"steps = {steps}")
    return marsden.Problem.from_toml(text).solve(every=1)


def test_the_3d_pendulum_keeps_its_vertical_momentum_and_its_joint():
    s = pendulum_3d()
    body = s.bodies["body"]
    assert body.R.shape == (len(s), 3, 3) and body.Pi.shape == (len(s), 3)
    assert body.x.shape == (len(s), 3) and body.p.shape == (len(s), 3)
    # L_z = e3·(RΠ + x × p) about the pivot at the origin (R22).
    spin = np.einsum("ki,ki->k", body.R[:, 2, :], body.Pi)
    lz = spin + body.x[:, 0] * body.p[:, 1] - body.x[:, 1] * body.p[:, 0]
    assert abs(lz[0]) > 0.1
    assert np.abs(lz - lz[0]).max() < 1e-12 * abs(lz[0])
    # The ball joint: x + R s = 0 with s = (0.05, 0, 0.4) in the body.
    pivot = body.x + np.einsum("kij,j->ki", body.R, [0.05, 0.0, 0.4])
    assert np.abs(pivot).max() < 1e-13
    assert s.constraint_residual.max() < 1e-13
    assert s.constraint_velocity_residual.max() < 1e-13
    assert s.multipliers.shape == (len(s), 3)
    assert s.summary["multibody"]["joints"][0]["name"] == "pivot"


def test_the_bodies_are_those_of_the_command(tmp_path, cli):
    s = pendulum_3d(steps=200)
    out = tmp_path / "out"
    subprocess.run([cli, "run", str(EXAMPLES / "pendulum_3d.toml"), "--steps",
                    "200", "--out", str(out), "-q"], check=True)
    summary = json.loads((out / "summary.json").read_text())
    final = np.array(summary["multibody"]["final_attitudes"]["body"])
    assert np.array_equal(s.bodies["body"].R[-1], final)


def test_a_joint_naming_an_unknown_body_is_a_problem_error():
    text = (EXAMPLES / "pendulum_3d.toml").read_text().replace(
        'bodies = ["ground", "body"]', 'bodies = ["ground", "rod"]')
    with pytest.raises(marsden.ProblemError, match="unknown body `rod`"):
        marsden.Problem.from_toml(text).solve()
