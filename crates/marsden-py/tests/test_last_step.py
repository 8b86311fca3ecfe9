"""A t_end that is not a whole number of steps: the run ends there with one shorter step."""

from __future__ import annotations

import math

import marsden


def test_t_end_off_the_grid_ends_there_with_a_shorter_step():
    """t_end = 20π is no whole number of h = 0.01: 6283 steps of h and one of 20π − 62.83.
    The midpoint rule keeps the oscillator's H = (q² + p²)/2 at every step whatever its size
    (a quadratic invariant, reference case R1), and the state is the exact flow's to O(h²)."""
    problem = marsden.Problem(lagrangian="0.5*x_dot^2 - 0.5*x^2", coordinates=["x"],
                              q0=[1.0], v0=[0.0], h=0.01, t_end=20 * math.pi)
    solution = problem.solve()
    assert solution.t[-1] == 20 * math.pi
    assert solution.summary["steps"] == 6284
    assert abs(solution.summary["last_step"] - (20 * math.pi - 6283 * 0.01)) < 1e-12
    q, p = solution.q[-1][0], solution.p[-1][0]
    assert abs(0.5 * (q * q + p * p) - 0.5) < 1e-12
    assert abs(q - 1.0) < 1e-3 and abs(p) < 1e-3
