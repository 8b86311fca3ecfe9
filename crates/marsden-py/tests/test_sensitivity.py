"""Derivatives of a run from Python: ``solve(sensitivity=...)`` against central differences
of whole runs, the Jacobians' layout, area preservation, and pointed errors."""

from __future__ import annotations

import numpy as np
import pytest

import marsden

#: A pendulum of length l in gravity g (m = 1), started from rest: L = ½ l² θ̇² + g l cos θ.
LAGRANGIAN = "0.5*l^2*theta_dot^2 + g*l*cos(theta)"
H, STEPS = 0.01, 500


def pendulum(g: float = 9.81, l: float = 1.3, theta0: float = 1.0, p0: float = 0.0,
             method: str = "midpoint", steps: int = STEPS) -> marsden.Problem:
    return marsden.Problem(lagrangian=LAGRANGIAN, coordinates=["theta"],
                           parameters={"g": g, "l": l}, q0=[theta0], p0=[p0],
                           method=method, h=H, steps=steps)


def final(problem: marsden.Problem) -> np.ndarray:
    s = problem.solve(every=STEPS)
    return np.concatenate([s.q[-1], s.p[-1]])


def central(make, value: float, delta: float = 1e-6) -> np.ndarray:
    return (final(make(value + delta)) - final(make(value - delta))) / (2 * delta)


def agree(derivative: np.ndarray, reference: np.ndarray, tolerance: float = 1e-6) -> None:
    scale = max(np.max(np.abs(reference)), 1e-300)
    assert np.max(np.abs(derivative - reference)) / scale < tolerance, (derivative, reference)


@pytest.mark.parametrize("method", ["midpoint", "gauss-2"])
def test_parameter_columns_match_central_differences_of_whole_runs(method):
    solution = pendulum(method=method).solve(sensitivity=["g", "l"])
    s = solution.sensitivity
    assert s.rows == ["q_theta", "p_theta"] and s.columns == ["g", "l"]
    agree(s.column("g"), central(lambda g: pendulum(g=g, method=method), 9.81))
    agree(s.column("l"), central(lambda l: pendulum(l=l, method=method), 1.3))


def test_initial_columns_match_central_differences_and_preserve_area():
    solution = pendulum().solve(sensitivity=True)
    s = solution.sensitivity
    assert s.columns == ["q0_theta", "p0_theta"]
    agree(s.column("q0_theta"), central(lambda q: pendulum(theta0=q), 1.0))
    agree(s.column("p0_theta"), central(lambda p: pendulum(p0=p), 0.0))
    # One degree of freedom: a symplectic map preserves area, det = 1 at every stored step.
    determinants = np.linalg.det(s.jacobians)
    assert np.max(np.abs(determinants - 1.0)) < 1e-10


def test_stored_jacobians_follow_the_samples_and_end_at_the_final_one():
    solution = pendulum().solve(every=50, sensitivity={"initial": True, "parameters": ["g"]})
    s = solution.sensitivity
    assert s.jacobians.shape == (len(s.t), 2, 3)
    # One Jacobian per stored sample, at the same times (the first is at t0).
    np.testing.assert_allclose(s.t, solution.t, rtol=0, atol=1e-12)
    assert np.array_equal(s.jacobians[-1], s.final)
    np.testing.assert_array_equal(solution.summary["sensitivity"]["final"], s.final)


def test_a_sensitivity_table_in_the_file_fills_the_solution_too():
    text = pendulum().toml + "\n[sensitivity]\nparameters = [\"l\"]\n"
    problem = marsden.Problem.from_toml(text)
    assert problem.solve().sensitivity.columns == ["l"]
    with pytest.raises(marsden.ProblemError, match="already has a \\[sensitivity\\] table"):
        problem.solve(sensitivity=["g"])


def test_without_sensitivity_there_is_none():
    assert pendulum(steps=10).solve().sensitivity is None


@pytest.mark.parametrize("request_, message", [
    (["mass"], "not a parameter"),
    (False, "asks for no derivative"),
    ("g", "a list of names"),
    ({"parameter": ["g"]}, "unknown key"),
])
def test_bad_requests_raise_problem_error(request_, message):
    with pytest.raises(marsden.ProblemError, match=message):
        pendulum(steps=10).solve(sensitivity=request_)


def test_derivatives_that_cannot_be_computed_raise_with_the_run_kept():
    problem = pendulum(method="exact", steps=5)
    with pytest.raises(marsden.SimulationError, match="derivatives could not be computed") as e:
        problem.solve(sensitivity=True)
    assert e.value.solution.ok and len(e.value.solution) == 6
