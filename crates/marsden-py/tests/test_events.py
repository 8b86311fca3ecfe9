"""``Solution.events`` and ``Solution.observables``: the crossings located by ``[[events]]``
(R7: the pendulum's zeros at T/4 + jT/2, T = 4K(sin²(θ₀/2))) and the observables' columns
against the same expressions of the samples."""

from __future__ import annotations

import math

import numpy as np
import pytest

import marsden

PENDULUM = """
[system]
coordinates = ["theta"]
parameters = { m = 1.0, l = 1.0, g = 1.0 }
lagrangian = "0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)"
[initial]
q = [1.5]
v = [0.0]
[integrator]
method = "midpoint"
h = 0.005
t_end = 22.0
tolerance = 1e-14
[[events]]
name = "down"
when = "theta"
direction = "down"
[[events]]
name = "stop"
when = "theta"
direction = "up"
action = "stop"
count = 2
[output]
every = 10
observables = { x = "l*sin(theta)", w = "theta_dot" }
"""


def quarter_period(theta0: float) -> float:
    """K(m) with m = sin²(θ₀/2), by the arithmetic–geometric mean: K = π / (2 AGM(1, √(1−m)))."""
    a, b = 1.0, math.sqrt(1.0 - math.sin(theta0 / 2) ** 2)
    for _ in range(40):
        a, b = (a + b) / 2, math.sqrt(a * b)
    return math.pi / (2 * a)


def test_events_are_the_pendulum_zeros_by_name_and_a_stop_ends_the_run():
    s = marsden.Problem.from_toml(PENDULUM).solve()
    quarter = quarter_period(1.5)
    period = 4 * quarter
    assert s.status == "stopped by event stop"
    assert list(s.events) == ["down", "stop"]
    down, up = s.events["down"], s.events["stop"]
    # θ falls through 0 at T/4 and 5T/4; rises at 3T/4 and 7T/4, the second rise stops the run.
    np.testing.assert_allclose(down["t"], [quarter, quarter + period], atol=1e-4)
    np.testing.assert_allclose(up["t"], [3 * quarter, 3 * quarter + period], atol=1e-4)
    assert down["q"].shape == (2, 1) and up["p"].shape == (2, 1)
    assert np.all(np.abs(down["q"]) < 1e-12) and np.all(down["p"] < 0) and np.all(up["p"] > 0)
    assert s.summary["events"] == {"down": 2, "stop": 2}
    assert s.t[-1] >= up["t"][-1] > s.t[-1] - 0.005


def test_observables_are_the_same_expressions_of_the_samples():
    s = marsden.Problem.from_toml(PENDULUM).solve()
    assert list(s.observables) == ["x", "w"]
    np.testing.assert_allclose(s.observables["x"], np.sin(s.q[:, 0]), rtol=0, atol=1e-15)
    np.testing.assert_allclose(s.observables["w"], s.v[:, 0], rtol=0, atol=1e-14)
    assert len(s.observables["x"]) == len(s)


def test_a_problem_without_events_has_empty_dictionaries():
    s = marsden.Problem.from_toml(PENDULUM.split("[[events]]")[0]).solve()
    assert s.events == {} and s.observables == {}
    assert s.status == "completed"


def test_bad_events_are_problem_errors():
    with pytest.raises(marsden.ProblemError, match="unknown direction"):
        marsden.Problem.from_toml(PENDULUM.replace('direction = "down"', 'direction = "no"'))
