"""Rigid bodies from Python: the keywords of ``rigid_body`` files, ``Solution.R``, ``Pi`` and
``quaternion``, the same bits as ``marsden run`` on ``examples/heavy_top.toml`` (reference case
R20: the heavy symmetric top of Simo & Wong), a SymPy potential in the entries of R, and the
refusals as ``ProblemError``."""

from __future__ import annotations

import json
import subprocess

import numpy as np
import pytest
import sympy

import marsden
from conftest import EXAMPLES


def heavy_top(**kwargs) -> marsden.Problem:
    return marsden.Problem(**{**dict(
        rigid_body={"inertia": [5.0, 5.0, 1.0]}, parameters={"mgl": 20.0},
        potential="mgl*R33", rotation="z", body_rotation="z",
        rotation_vector0=[0.05, 0.0, 0.0], Omega0=[0.0, 0.0, 50.0],
        method="trapezoid", h=0.001, steps=2000), **kwargs})


def test_the_heavy_top_keeps_its_rotation_its_vertical_momentum_and_its_spin():
    s = heavy_top().solve(every=10)
    assert s.R.shape == (len(s), 3, 3) and s.Pi.shape == (len(s), 3)
    gram = np.einsum("kji,kjl->kil", s.R, s.R) - np.eye(3)
    assert np.abs(gram).max() < 1e-13
    # e3·RΠ (rotations about the vertical) and Π3 (about the symmetry axis), R20.
    lz = np.einsum("ki,ki->k", s.R[:, 2, :], s.Pi)
    assert np.abs(lz - lz[0]).max() < 1e-11
    assert np.allclose(s.momenta["L_z"], lz, rtol=0, atol=1e-12)
    assert np.abs(s.Pi[:, 2] - 50.0).max() < 1e-12
    q = s.quaternion
    assert q.shape == (len(s), 4) and np.all(q[:, 0] >= 0)
    assert np.allclose(np.linalg.norm(q, axis=1), 1.0, atol=1e-14)
    # The rotation of the first quaternion is 0.05 rad about e1: q = (cos 0.025, sin 0.025, 0, 0).
    assert q[0] == pytest.approx([np.cos(0.025), np.sin(0.025), 0.0, 0.0], abs=1e-15)


def test_keywords_and_the_file_give_the_same_bits_as_the_command(cli, tmp_path):
    text = (EXAMPLES / "heavy_top.toml").read_text()
    from_file = marsden.Problem.from_toml(text).solve()
    subprocess.run([cli, "run", str(EXAMPLES / "heavy_top.toml"), "--out", str(tmp_path),
                    "--quiet"], check=True)
    summary = json.loads((tmp_path / "summary.json").read_text())
    final = np.array(summary["rigid_body"]["final_attitude"])
    assert np.array_equal(from_file.R[-1], final)
    assert np.array_equal(from_file.Pi[-1], summary["rigid_body"]["final_body_momentum"])
    keywords = heavy_top(steps=20000).solve()
    assert np.array_equal(keywords.R[-1], final)


def test_a_sympy_potential_in_the_entries_of_r_gives_the_same_run():
    mgl, r33 = sympy.symbols("mgl R33")
    a = heavy_top(potential=mgl * r33, steps=300).solve()
    b = heavy_top(steps=300).solve()
    assert np.array_equal(a.R, b.R) and np.array_equal(a.Pi, b.Pi)


def test_a_free_body_with_a_mass_falls_and_a_matrix_attitude_is_taken_as_given():
    r0 = [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]
    s = marsden.Problem(rigid_body={"inertia": [1.0, 2.0, 2.5], "mass": 2.0},
                        parameters={"g": 9.81}, potential="2*g*z", R0=r0,
                        Pi0=[0.0, 0.0, 0.0], q0=[0.0, 0.0, 1.0], v0=[0.0, 0.0, 0.0],
                        h=0.01, steps=10).solve()
    assert s.coordinates == ["x", "y", "z"]
    assert s.q[-1, 2] == pytest.approx(1.0 - 0.5 * 9.81 * 0.1 ** 2, abs=1e-12)
    assert np.array_equal(s.R[0], np.array(r0))


def test_bad_rigid_bodies_raise_problem_errors_naming_the_keyword():
    with pytest.raises(marsden.ProblemError, match="invalid inertia.*not positive definite"):
        heavy_top(rigid_body={"inertia": [5.0, -5.0, 1.0]})
    with pytest.raises(marsden.ProblemError, match="has no rigid-body version"):
        heavy_top(method="gauss-2")
    with pytest.raises(marsden.ProblemError, match="unknown name `R34`"):
        heavy_top(potential="mgl*R34")
    with pytest.raises(marsden.ProblemError, match="not a rotation"):
        heavy_top(rotation_vector0=None, R0=[[1, 0, 0], [0, 1, 0.01], [0, 0, 1]])
    with pytest.raises(marsden.ProblemError, match="unknown key 'moments'"):
        heavy_top(rigid_body={"moments": [1, 2, 3]})
