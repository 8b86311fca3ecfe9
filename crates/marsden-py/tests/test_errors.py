"""Bad input raises ProblemError with the command's pointed message; a run through a
singularity raises SimulationError carrying the finite states before it."""

from __future__ import annotations

import numpy as np
import pytest

import marsden
from conftest import PENDULUM


def test_problem_error_is_a_value_error_with_a_caret_in_the_expression():
    with pytest.raises(marsden.ProblemError) as info:
        marsden.Problem(**{**PENDULUM, "lagrangian": "0.5*m*l^2*theta_dot^2 + m*gg*l*cos(theta)"},
                        steps=10)
    assert isinstance(info.value, ValueError)
    message = str(info.value)
    assert "unknown name `gg`" in message, message
    assert "--> in lagrangian=" in message and "^^" in message, message
    assert "known names: g, l, m" in message, message


def test_wrong_number_of_initial_positions():
    with pytest.raises(marsden.ProblemError) as info:
        marsden.Problem(**{**PENDULUM, "q0": [1.5, 0.0]}, steps=10)
    message = str(info.value)
    assert "q0 has 2 values, but the system has 1" in message, message
    assert "--> in q0=" in message and "<python>" not in message, message


def test_bad_method_names_the_closest():
    with pytest.raises(marsden.ProblemError) as info:
        marsden.Problem(**{**PENDULUM, "method": "midpiont"}, steps=10)
    assert "did you mean `midpoint`?" in str(info.value), str(info.value)


@pytest.mark.parametrize("h", [float("nan"), float("inf"), -0.1, 0.0])
def test_non_finite_or_non_positive_h(h):
    with pytest.raises(marsden.ProblemError) as info:
        marsden.Problem(**{**PENDULUM, "h": h}, steps=10)
    assert "h must be a positive, finite time step" in str(info.value), str(info.value)
    assert "--> in h=" in str(info.value), str(info.value)


def test_toml_errors_point_into_the_text():
    text = "[system]\nbuiltin = \"pendulum\"\n[initial]\nq = [1.0]\nv = [0.0]\n" \
           "[integrator]\nh = 0.1\nstesp = 10\n"
    with pytest.raises(marsden.ProblemError) as info:
        marsden.Problem.from_toml(text, "cell.toml")
    message = str(info.value)
    assert "cell.toml:8:1" in message and "stesp" in message, message


def test_a_collision_raises_simulation_error_with_the_states_before_it():
    """Kepler with zero angular momentum falls into the singularity at r = 0 (at
    t = π/(2√2) ≈ 1.11 from r = 1 at rest, μ = 1): the run fails there."""
    problem = marsden.Problem(
        lagrangian="0.5*(x_dot^2 + y_dot^2) + mu/sqrt(x^2 + y^2)", coordinates=["x", "y"],
        parameters={"mu": 1.0}, q0=[1.0, 0.0], v0=[0.0, 0.0], h=0.01, steps=1000)
    with pytest.raises(marsden.SimulationError) as info:
        problem.solve()
    solution = info.value.solution
    assert solution.status == "failed" and solution.error
    assert 0 < len(solution) < 1001
    assert np.all(np.isfinite(solution.q)) and np.all(np.isfinite(solution.p))
    assert solution.t[-1] < 1.12
    assert solution.summary["status"] == "failed"
