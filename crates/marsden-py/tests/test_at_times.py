"""``times``: the state at chosen times, between grid points too (``solution.at_times``)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import marsden


def oscillator(h: float, times, **extra) -> marsden.Problem:
    """The oscillator L = ½ẋ² − ½x² from x = 1 at rest: x(t) = cos t, p(t) = −sin t."""
    return marsden.Problem(lagrangian="0.5*x_dot^2 - 0.5*x^2", coordinates=["x"], q0=[1.0],
                           v0=[0.0], h=h, t_end=8.0, tolerance=1e-14, times=times, **extra)


def test_samples_follow_the_closed_form_at_order_two():
    """At e, π and 7.7 (between grid points for every h = 1/16 … 1/64) the samples follow
    x = cos t, p = −sin t with an error that falls fourfold per halving of h (the midpoint
    rule's order 2); at t = 4, a grid time, the sample is the stored row itself."""
    times = [math.e, 4.0, math.pi, 7.7]
    times.sort()
    errors = []
    for h in [1 / 16, 1 / 32, 1 / 64]:
        s = oscillator(h, times).solve()
        at = s.at_times
        assert at is not None and list(at["t"]) == times
        assert at["q"].shape == (4, 1) and at["p"].shape == (4, 1)
        k = int(round(4.0 / h))
        j = times.index(4.0)
        assert s.t[k] == 4.0
        assert at["q"][j, 0] == s.q[k, 0] and at["p"][j, 0] == s.p[k, 0]
        t = np.array(times)
        error = max(np.max(np.abs(at["q"][:, 0] - np.cos(t))),
                    np.max(np.abs(at["p"][:, 0] + np.sin(t))))
        assert error < 0.2 * h
        errors.append(error)
    ratios = [errors[0] / errors[1], errors[1] / errors[2]]
    assert all(3.6 < r < 4.4 for r in ratios), (errors, ratios)


def test_observables_at_the_samples_and_a_run_without_times():
    """Observables are columns of the samples; a problem without ``times`` has none."""
    text = """
[system]
coordinates = ["x"]
lagrangian = "0.5*x_dot^2 - 0.5*x^2"
[initial]
q = [1.0]
v = [0.0]
[integrator]
h = 0.01
t_end = 2
[output]
times = [0.505, 1.5]
observables = { H = "0.5*x_dot^2 + 0.5*x^2" }
"""
    s = marsden.Problem.from_toml(text).solve()
    at = s.at_times
    H = at["observables"]["H"]
    q, p = at["q"][:, 0], at["p"][:, 0]
    assert np.allclose(H, 0.5 * (q * q + p * p), rtol=0, atol=1e-15)
    assert np.all(np.abs(H - 0.5) < 1e-4)
    assert oscillator(0.1, None).solve().at_times is None


def test_bad_times_raise_problem_error_with_the_reason():
    with pytest.raises(marsden.ProblemError, match="not after the one before it"):
        oscillator(0.1, [2.0, 1.0])
    with pytest.raises(marsden.ProblemError, match="outside the run"):
        oscillator(0.1, [9.0])
    with pytest.raises(marsden.ProblemError, match="times: expected a list of numbers"):
        oscillator(0.1, 3.0)


def test_exact_times_are_the_ends_of_runs_stopping_there():
    """``exact_times=True``: the sample at e is, to the bit, the last state of the same problem
    with ``t_end = e`` (its last step is the shorter one the sample was reached by), and the
    run's own states are those of the run without it."""
    exact = oscillator(0.1, [math.e], exact_times=True).solve()
    plain = oscillator(0.1, None).solve()
    assert exact.summary["samples"]["reached_by"] == "step"
    ended = marsden.Problem(lagrangian="0.5*x_dot^2 - 0.5*x^2", coordinates=["x"], q0=[1.0],
                            v0=[0.0], h=0.1, t_end=math.e, tolerance=1e-14).solve()
    assert ended.t[-1] == math.e
    assert exact.at_times["q"][0, 0] == ended.q[-1, 0]
    assert exact.at_times["p"][0, 0] == ended.p[-1, 0]
    assert np.array_equal(exact.q, plain.q) and np.array_equal(exact.p, plain.p)
    with pytest.raises(marsden.ProblemError, match="needs the times to reach"):
        oscillator(0.1, None, exact_times=True)
