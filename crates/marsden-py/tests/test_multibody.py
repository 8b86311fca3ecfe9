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


def test_keywords_give_the_example_files_bits():
    """The keywords ``gravity``, ``bodies``, ``joints``, ``springs`` and ``bodies0`` write the
    example files' tables: the compound double pendulum (two revolute joints under gravity) and
    the spring dumbbell run to the same bits as the files themselves."""
    pendulum = marsden.Problem(
        name="compound_double_pendulum", gravity=[0.0, 0.0, -9.81],
        bodies=[{"name": "a", "mass": 1.0, "inertia": [1 / 12, 1 / 12, 0.001]},
                {"name": "b", "mass": 1.0, "inertia": np.array([1 / 12, 1 / 12, 0.001])}],
        joints=[{"name": "shoulder", "kind": "revolute", "bodies": ["ground", "a"],
                 "at": [[0.0, 0.0, 0.0], [0.0, 0.0, 0.5]],
                 "axis": [[0.0, 1.0, 0.0], [0.0, 1.0, 0.0]]},
                {"name": "elbow", "kind": "revolute", "bodies": ["a", "b"],
                 "at": [[0.0, 0.0, -0.5], [0.0, 0.0, 0.5]],
                 "axis": [[0.0, 1.0, 0.0], [0.0, 1.0, 0.0]]}],
        bodies0={"a": {"rotation_vector": [0.0, 0.9, 0.0],
                       "x": [-0.3916634548137417, 0.0, -0.3108049841353322]},
                 "b": {"rotation_vector": [0.0, -0.4, 0.0],
                       "x": [-0.5886177384731581, 0.0, -1.082140465272107]}},
        method="trapezoid", h=0.001, steps=300)
    dumbbell = marsden.Problem(
        name="spring_dumbbell",
        bodies=[{"name": "a", "mass": 1.0, "inertia": [0.02, 0.03, 0.04]},
                {"name": "b", "mass": 0.5, "inertia": [0.01, 0.012, 0.015]}],
        springs=[{"name": "link", "bodies": ["a", "b"],
                  "at": [[0.1, 0.0, 0.0], [-0.1, 0.0, 0.0]], "stiffness": 50.0,
                  "rest_length": 1.0}],
        bodies0={"a": {"x": [-0.7, 0.0, 0.0], "v": [0.0, -0.1, 0.05], "Omega": [0.0, 0.5, 2.0]},
                 "b": {"x": [0.7, 0.0, 0.0], "v": [0.0, 0.2, 0.0], "Omega": [1.0, 0.0, -1.5]}},
        method="trapezoid", h=0.005, steps=300)
    for problem, example, t_end in [(pendulum, "compound_double_pendulum.toml", "t_end = 10.0"),
                                    (dumbbell, "spring_dumbbell.toml", "t_end = 20.0")]:
        text = (EXAMPLES / example).read_text().replace(t_end, "steps = 300")
        from_file = marsden.Problem.from_toml(text).solve(every=1)
        from_keywords = problem.solve(every=1)
        for name in ("a", "b"):
            a, b = from_keywords.bodies[name], from_file.bodies[name]
            assert np.array_equal(a.R, b.R) and np.array_equal(a.x, b.x)
            assert np.array_equal(a.Pi, b.Pi) and np.array_equal(a.p, b.p)


def test_body_keywords_with_unknown_keys_say_which():
    with pytest.raises(marsden.ProblemError, match=r"joints\[0\]: unknown key\(s\) \['axes'\]"):
        marsden.Problem(bodies=[{"name": "a", "mass": 1.0, "inertia": [1, 1, 1]}],
                        joints=[{"kind": "revolute", "bodies": ["ground", "a"], "axes": []}],
                        h=0.01, steps=10)
    with pytest.raises(marsden.ProblemError, match="bodies: expected a list of dictionaries"):
        marsden.Problem(bodies={"name": "a"}, h=0.01, steps=10)


def test_a_particle_has_a_position_and_no_attitude():
    """``examples/pendulum_with_bob.toml``: a rod hinged at its top with a particle on a ball
    joint at its tip. ``Solution.bodies["bob"]`` has ``x``, ``p`` and no ``R``/``Pi``; the bob
    stays at the rod's tip ``x_rod − R_rod (0, 0, 0.5)``; the keywords ``particles=`` write the
    file's ``[[system.particle]]`` and run to the same bits."""
    text = (EXAMPLES / "pendulum_with_bob.toml").read_text().replace("t_end = 10.0", "steps = 300")
    s = marsden.Problem.from_toml(text).solve(every=1)
    rod, bob = s.bodies["rod"], s.bodies["bob"]
    assert bob.R is None and bob.Pi is None
    assert rod.R.shape == (len(s), 3, 3) and bob.x.shape == (len(s), 3)
    tip = rod.x - np.einsum("kij,j->ki", rod.R, [0.0, 0.0, 0.5])
    assert np.abs(tip - bob.x).max() < 1e-13
    assert s.summary["multibody"]["particles"] == 1
    keywords = marsden.Problem(
        name="pendulum_with_bob", gravity=[0.0, 0.0, -9.81],
        bodies=[{"name": "rod", "mass": 1.0, "inertia": [1 / 12, 1 / 12, 0.001]}],
        particles=[{"name": "bob", "mass": 0.5}],
        joints=[{"name": "hinge", "kind": "revolute", "bodies": ["ground", "rod"],
                 "at": [[0.0, 0.0, 0.0], [0.0, 0.0, 0.5]],
                 "axis": [[0.0, 1.0, 0.0], [0.0, 1.0, 0.0]]},
                {"name": "ball", "kind": "spherical", "bodies": ["rod", "bob"],
                 "at": [[0.0, 0.0, -0.5], [0.0, 0.0, 0.0]]}],
        bodies0={"rod": {"rotation_vector": [0.0, 0.8, 0.0], "Omega": [0.0, -0.6, 0.0],
                         "x": [-0.3586780454497614, 0.0, -0.3483533546735827],
                         "v": [0.2090120128041496, 0.0, -0.21520682726985682]},
                 "bob": {"x": [-0.7173560908995228, 0.0, -0.6967067093471654],
                         "v": [0.4180240256082992, 0.0, -0.43041365453971364]}},
        method="trapezoid", h=0.01, steps=300).solve(every=1)
    assert np.array_equal(keywords.bodies["bob"].x, bob.x)
    assert np.array_equal(keywords.bodies["rod"].R, rod.R)
    with pytest.raises(marsden.ProblemError, match="particle `bob` has no attitude"):
        marsden.Problem.from_toml(text.replace("[initial.bob]\n", "[initial.bob]\nR = "
                                               "[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]\n"))
