"""``Problem.optimize()``: optimal control problems (``[optimal_control]``) from Python, against
the double integrator's closed form (Bryson & Ho 1975: rest to rest from 0 to 1 in T = 1 with
cost ∫ ½u², optimum u(t) = 6 − 12t of cost 6) and the ``marsden optimize`` command."""

from __future__ import annotations

import json
import subprocess

import numpy as np
import pytest

import marsden

DOUBLE_INTEGRATOR = """
[system]
coordinates = ["x"]
lagrangian = "0.5*x_dot^2"
controls = ["u"]
forces = ["u"]
[optimal_control]
cost = "0.5*u^2"
t_end = 1.0
steps = 40
start = { q = [0.0], v = [0.0] }
end = { q = [1.0], v = [0.0] }
"""


def test_double_integrator_against_the_closed_form() -> None:
    problem = marsden.Problem.from_toml(DOUBLE_INTEGRATOR)
    assert problem.is_optimal_control
    s = problem.optimize()
    assert s.status == "converged" and s.converged
    assert s.q.shape == (41, 1) and s.p.shape == (41, 1) and s.u.shape == (40, 1)
    # The midpoint transcription's optimum costs 6 N²/(N² − 1) → 6 at order 2.
    assert abs(s.cost - 6.0) < 6.0 / 40**2 * 1.01
    h = 1.0 / 40
    midpoints = s.t[:-1] + h / 2
    assert np.max(np.abs(s.u[:, 0] - (6 - 12 * midpoints))) < 10 * h * h
    assert abs(s.q[-1, 0] - 1.0) < 1e-10 and abs(s.p[-1, 0]) < 1e-10
    oc = s.summary["optimal_control"]
    assert oc["status"] == "converged" and oc["iterations"] >= 1
    assert oc["constraint_violation"] <= 1e-10


def test_the_same_numbers_as_the_command(cli: str, tmp_path) -> None:
    path = tmp_path / "di.toml"
    path.write_text(DOUBLE_INTEGRATOR)
    out = tmp_path / "out"
    subprocess.run([cli, "optimize", str(path), "--out", str(out), "--quiet"], check=True)
    summary = json.loads((out / "summary.json").read_text())
    s = marsden.Problem.load(path).optimize()
    assert s.cost == summary["optimal_control"]["cost"]


def test_iteration_limit_returns_the_last_iterate() -> None:
    text = DOUBLE_INTEGRATOR.replace("steps = 40", "steps = 40\nmax_iterations = 1")
    text = text.replace('lagrangian = "0.5*x_dot^2"', 'lagrangian = "0.5*x_dot^2 + cos(x)"')
    s = marsden.Problem.from_toml(text).optimize()
    assert s.status == "iteration limit"
    assert s.summary["optimal_control"]["last_iterate"] is True
    assert s.u.shape == (40, 1)


def test_bad_input_and_the_wrong_call() -> None:
    with pytest.raises(marsden.ProblemError, match="control `w` is not used by any force"):
        marsden.Problem.from_toml(DOUBLE_INTEGRATOR.replace('["u"]\nforces', '["u", "w"]\nforces'))
    with pytest.raises(marsden.ProblemError, match="optimize"):
        marsden.Problem.from_toml(DOUBLE_INTEGRATOR).solve()
    pendulum = marsden.Problem.builtin("pendulum", q0=[1.0], v0=[0.0], h=0.1, steps=10)
    with pytest.raises(marsden.ProblemError, match="no \\[optimal_control\\]"):
        pendulum.optimize()


def test_optimal_control_from_keywords_is_the_file() -> None:
    """``marsden.OptimalControl`` writes the file's ``[optimal_control]``: the same bits."""
    system = marsden.Problem("0.5*x_dot^2", coordinates="x", q0=[0.0], v0=[0.0], h=0.1,
                             steps=10)
    oc = marsden.OptimalControl(system, controls=["u"], forces=["u"], cost="0.5*u^2",
                                t_end=1.0, steps=40, start={"q": [0.0], "v": [0.0]},
                                end={"q": [1.0], "v": [0.0]})
    assert "[initial]" not in oc.toml and "[integrator]" not in oc.toml
    s = oc.solve()
    reference = marsden.Problem.from_toml(DOUBLE_INTEGRATOR).optimize()
    assert s.status == "converged"
    assert s.cost == reference.cost
    assert np.array_equal(s.u, reference.u) and np.array_equal(s.q, reference.q)
    assert np.array_equal(s.t_u, s.t[:-1])


def test_optimal_control_keywords_bounds_and_free_components() -> None:
    """A free end velocity: from rest at 0 to q(1) = ½, Pontryagin gives u(1) = 0, so
    u = a(1 − t) with a/3 = ½: cost a²/6 = 0.375 (order 2 in h). With |u| ≤ 1.2 < a = 1.5 the
    bound binds: it holds at every step and the cost rises."""
    system = marsden.Problem("0.5*x_dot^2", coordinates="x", q0=[0.0], v0=[0.0], h=0.1,
                             steps=10)

    def solve(**extra):
        return marsden.OptimalControl(system, controls="u", forces=["u"], cost="0.5*u^2",
                                      t_end=1.0, steps=40, start={"q": [0.0], "v": [0.0]},
                                      end={"q": [0.5], "v": ["free"]}, **extra).solve()

    free = solve()
    assert free.status == "converged"
    assert abs(free.cost - 0.375) < 1e-3
    assert abs(free.u[-1, 0] - 1.5 / 80) < 1e-3  # a(1 − t) at the last midpoint
    bounded = solve(bounds={"u": [-1.2, 1.2]})
    assert bounded.status == "converged"
    assert np.max(np.abs(bounded.u)) <= 1.2 + 1e-9
    assert bounded.cost > free.cost + 1e-3


def test_optimal_control_refuses_bad_keywords() -> None:
    system = marsden.Problem("0.5*x_dot^2", coordinates="x", q0=[0.0], v0=[0.0], h=0.1,
                             steps=10)
    with pytest.raises(marsden.ProblemError, match="`exact` cannot be used for optimal control"):
        marsden.OptimalControl(system, controls=["u"], forces=["u"], cost="0.5*u^2",
                               t_end=1.0, steps=10, start={"q": [0.0], "v": [0.0]},
                               end={"q": [1.0], "v": [0.0]}, method="exact")
    with pytest.raises(marsden.ProblemError, match="unknown name `k`"):
        marsden.OptimalControl(system, controls=["u"], forces=["u"], cost="0.5*u^2 + k",
                               t_end=1.0, steps=10, start={"q": [0.0], "v": [0.0]},
                               end={"q": [1.0], "v": [0.0]})


def test_gauss_two_takes_a_control_per_node() -> None:
    """``gauss-2``: two control values per step at ``t_k + (1/2 ∓ √3/6) h``; the double
    integrator's optimum u = 6 − 12t is affine, which the stage values reproduce exactly."""
    text = DOUBLE_INTEGRATOR.replace("steps = 40", 'steps = 10\nmethod = "gauss-2"')
    s = marsden.Problem.from_toml(text).optimize()
    assert s.status == "converged"
    assert s.u.shape == (20, 1) and s.t_u.shape == (20,)
    h = 0.1
    c = np.array([0.5 - np.sqrt(3) / 6, 0.5 + np.sqrt(3) / 6])
    assert np.allclose(s.t_u, (np.arange(10)[:, None] * h + c * h).ravel(), atol=1e-15)
    assert np.max(np.abs(s.u[:, 0] - (6 - 12 * s.t_u))) < 1e-8
    assert abs(s.cost - 6.0) < 1e-9
    assert s.summary["optimal_control"]["controls_per_step"] == 2


def test_path_inequality_bryson_denham() -> None:
    """The Bryson–Denham problem (Bryson & Ho 1975 §3.11): from ``(x, v) = (0, 1)`` to
    ``(0, −1)`` in T = 1 with cost ∫ ½u² and the state constraint ``x ≤ 1/9`` as the path
    inequality ``x − 1/9 ≤ 0`` (a string, then SymPy): the continuous optimum costs 4; the
    midpoint discretisation at N = 40 costs 4.0051 (its O(h²) error, 4 at order 2 as the
    command's test shows), meets the inequality at every midpoint and reports it."""
    sp = pytest.importorskip("sympy")
    system = marsden.Problem("0.5*x_dot^2", coordinates="x", q0=[0.0], v0=[1.0], h=0.1,
                             steps=10)

    def solve(path):
        return marsden.OptimalControl(system, controls="u", forces=["u"], cost="0.5*u^2",
                                      t_end=1.0, steps=40, start={"q": [0.0], "v": [1.0]},
                                      end={"q": [0.0], "v": [-1.0]}, path=path).solve()

    s = solve(["x - 1/9"])
    assert s.status == "converged"
    assert abs(s.cost - 4.0) < 6e-3 and s.cost > 4.0
    midpoints = 0.5 * (s.q[1:, 0] + s.q[:-1, 0])
    assert np.max(midpoints) <= 1 / 9 + 1e-10
    g = s.summary["optimal_control"]["path"][0]
    assert g["expression"] == "x - 1/9" and g["points"] == 40 and g["max"] <= 1e-10
    assert g["max_multiplier"] > 0
    x = sp.Symbol("x")
    again = solve([x - sp.Rational(1, 9)])
    assert abs(again.cost - s.cost) < 1e-12
    with pytest.raises(marsden.ProblemError, match=r"path\[0\]: unknown name `k`"):
        solve(["x - k"])
