"""Problems from keyword arguments, problem text and files: the same code path as the `marsden`
command, so the same bits (the pendulum and Kepler examples, and the catalog)."""

from __future__ import annotations

import json
import pickle
import subprocess

import numpy as np
import pytest

import marsden
from conftest import EXAMPLES, PENDULUM


def run_cli(cli: str, path, tmp_path) -> dict:
    """`marsden run` on `path` writing into `tmp_path`; its summary.json."""
    out = tmp_path / "out"
    subprocess.run([cli, "run", str(path), "--out", str(out)], check=True,
                   capture_output=True)
    return json.loads((out / "summary.json").read_text())


@pytest.mark.parametrize("example", ["pendulum.toml", "kepler.toml", "cartesian_pendulum.toml",
                                     "damped_oscillator.toml"])
def test_from_toml_and_the_cli_give_the_same_final_state_bit_for_bit(cli, tmp_path, example):
    path = EXAMPLES / example
    summary = run_cli(cli, path, tmp_path)
    solution = marsden.Problem.from_toml(path.read_text(), str(path)).solve()
    final = solution.final_state()
    assert summary["status"] == solution.status == "completed"
    assert final["t"] == summary["final_state"]["t"]
    assert final["q"].tolist() == summary["final_state"]["q"]
    assert final["p"].tolist() == summary["final_state"]["p"]
    # The last stored sample is the final state.
    assert solution.q[-1].tolist() == summary["final_state"]["q"]
    assert solution.p[-1].tolist() == summary["final_state"]["p"]
    # The same diagnostics as summary.json (over the same stored samples).
    assert solution.summary["energy"] == summary["energy"]
    assert solution.summary["newton"] == summary["newton"]


def test_load_equals_from_toml():
    path = EXAMPLES / "pendulum.toml"
    a = marsden.Problem.load(path).solve(every=100)
    b = marsden.Problem.from_toml(path.read_text()).solve(every=100)
    assert np.array_equal(a.q, b.q) and np.array_equal(a.p, b.p)


def test_keyword_form_equals_the_problem_file_bit_for_bit():
    """examples/pendulum.toml written as keyword arguments: the same samples."""
    text = (EXAMPLES / "pendulum.toml").read_text()
    from_file = marsden.Problem.from_toml(text).solve(every=10)
    kwargs = marsden.Problem(**PENDULUM, steps=100000, tolerance=1e-12, max_iterations=50,
                             name="pendulum")
    solution = kwargs.solve(every=10)
    for field in ("t", "q", "p", "v", "energy"):
        assert np.array_equal(getattr(solution, field), getattr(from_file, field)), field
    assert solution.summary["final_state"] == from_file.summary["final_state"]


def test_builtin_and_catalog():
    names = [s["name"] for s in marsden.systems()]
    assert names[:5] == ["harmonic_oscillator", "free_fall", "pendulum", "double_pendulum",
                         "kepler"]
    kepler = next(s for s in marsden.systems() if s["name"] == "kepler")
    assert kepler["coordinates"] == ["x", "y"] and "mu" in kepler["parameters"]
    problem = marsden.Problem.builtin("kepler", q0=[0.4, 0.0], p0=[0.0, 2.0], h=0.01,
                                      steps=200, tolerance=1e-14,
                                      symmetries={"Lz": ["-y", "x"]})
    assert problem.coordinates == ["x", "y"] and problem.parameters == {"mu": 1.0}
    solution = problem.solve()
    # Kepler e = 0.6 (reference case R10): L_z = q_x p_y - q_y p_x = 0.8 is conserved
    # by the midpoint rule to round-off.
    assert abs(solution.momenta["Lz"][0] - 0.8) < 1e-15
    assert np.max(np.abs(solution.momenta["Lz"] - 0.8)) < 1e-12


def test_samples_have_one_row_per_stored_step():
    solution = marsden.Problem(**PENDULUM, steps=1000).solve(every=10)
    assert solution.t.shape == (101,) and solution.q.shape == (101, 1)
    assert solution.p.shape == solution.v.shape == (101, 1)
    assert solution.t[-1] == pytest.approx(50.0)
    # L = ½ θ̇² + cos θ with m = l = g = 1: p = θ̇ and E = ½ p² − cos θ.
    assert np.allclose(solution.v, solution.p, rtol=0, atol=1e-12)
    energy = 0.5 * solution.p[:, 0] ** 2 - np.cos(solution.q[:, 0])
    assert np.allclose(solution.energy, energy, rtol=0, atol=1e-12)
    # A symplectic method: bounded energy error, about 1e-3 at h = 0.05 (reference case
    # R8: pendulum, midpoint).
    assert solution.summary["energy"]["max_rel_error"] < 5e-3


def test_constraints_forces_and_t_end():
    cart = marsden.Problem(
        lagrangian="0.5*m*(x_dot^2 + y_dot^2) - m*g*y", coordinates=["x", "y"],
        parameters={"m": 1.0, "g": 1.0, "l": 1.0}, constraints=["x^2 + y^2 - l^2"],
        q0=[0.9974949866040544, -0.0707372016677029], v0=[0.0, 0.0], h=0.05, steps=200)
    s = cart.solve()
    assert s.constraint_residual is not None and np.max(s.constraint_residual) < 1e-10
    # The hidden constraint Dφ(q)·v = 2(x v_x + y v_y) = 0, held by the RATTLE projection.
    hidden = 2 * np.abs(s.q[:, 0] * s.v[:, 0] + s.q[:, 1] * s.v[:, 1])
    assert np.allclose(s.constraint_velocity_residual, hidden, rtol=0, atol=1e-13)
    assert np.max(s.constraint_velocity_residual) < 1e-10
    # R7's multiplier: with φ = x² + y² − l² and m = l = g = 1, a = −e_y − 2λq, so on the circle
    # λ = (|v|² − y)/2 (positive: the rod pulls inward; a wrong sign fails here).
    assert s.multipliers.shape == (len(s.t), 1)
    expected = 0.5 * (s.v[:, 0] ** 2 + s.v[:, 1] ** 2 - s.q[:, 1])
    assert np.min(expected) > 0.03
    assert np.allclose(s.multipliers[:, 0], expected, rtol=0, atol=1e-8)
    damped = marsden.Problem(
        lagrangian="0.5*m*x_dot^2 - 0.5*k*x^2", coordinates=["x"],
        parameters={"m": 1.0, "k": 4.0, "c": 0.1}, forces=["-c*x_dot"], q0=[1.0], v0=[0.0],
        h=0.02, t_end=30.0)
    d = damped.solve()
    assert d.t[-1] == pytest.approx(30.0)
    # E(t) ≈ E0 exp(-c t / m) for light damping: 2 exp(-3) ≈ 0.0996.
    assert d.energy[-1] == pytest.approx(2.0 * np.exp(-3.0), rel=0.05)


def test_problem_and_solution_pickle():
    problem = marsden.Problem(**PENDULUM, steps=100)
    again = pickle.loads(pickle.dumps(problem))
    assert again == problem and again.toml == problem.toml
    solution = problem.solve()
    copy = pickle.loads(pickle.dumps(solution))
    assert np.array_equal(copy.q, solution.q) and copy.summary == solution.summary


def test_reprs_say_what_ran():
    problem = marsden.Problem(**PENDULUM, steps=100)
    assert "theta" in repr(problem) and "midpoint" in repr(problem)
    text = repr(problem.solve())
    assert "completed" in text and "101 samples" in text and "max |ΔE/E0|" in text


def test_to_pandas_has_the_trajectory_columns():
    pd = pytest.importorskip("pandas")
    frame = marsden.Problem(**PENDULUM, steps=10).solve().to_pandas()
    assert isinstance(frame, pd.DataFrame)
    assert list(frame.columns) == ["t", "theta", "p_theta", "energy", "v_theta"]
    assert len(frame) == 11
