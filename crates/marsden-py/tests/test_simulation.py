"""``problem.simulation()``: a run taken in stretches (``step``, ``integrate``, ``state``),
saved and loaded."""

from __future__ import annotations

import math

import numpy as np
import pytest

import marsden


def oscillator(method: str = "midpoint", t_end: float = 4.0) -> marsden.Problem:
    """The oscillator L = ½ẋ² − ½x² from x = 1 at rest: x(t) = cos t, p(t) = −sin t."""
    return marsden.Problem(lagrangian="0.5*x_dot^2 - 0.5*x^2", coordinates=["x"], q0=[1.0],
                           v0=[0.0], h=0.01, t_end=t_end, method=method, tolerance=1e-14)


def test_stretches_on_the_grid_are_the_whole_run():
    """integrate(1), step(50), integrate(2) take the grid points of one run to t = 2: the
    explicit trapezoid (Störmer–Verlet) gives the same bits, the midpoint rule (a Newton solve
    per step, restarted without its predictor history at each stretch) the same states to the
    Newton tolerance."""
    for method, tolerance in [("trapezoid", 0.0), ("midpoint", 1e-13)]:
        whole = oscillator(method, t_end=2.0).solve()
        sim = oscillator(method).simulation()
        assert sim.state["t"] == 0.0 and sim.state["q"][0] == 1.0 and sim.state["p"][0] == 0.0
        first = sim.integrate(1.0)
        assert first.t[0] == 0.0 and first.t[-1] == 1.0 and len(first.t) == 101
        sim.step(50)
        assert sim.t == 1.5 and sim.steps == 150
        sim.integrate(2.0)
        assert sim.t == whole.t[-1] == 2.0 and sim.steps == 200
        assert abs(sim.q[0] - whole.q[-1, 0]) <= tolerance
        assert abs(sim.p[0] - whole.p[-1, 0]) <= tolerance
        # Within a stretch, the rows are the whole run's rows.
        assert np.max(np.abs(first.q[:, 0] - whole.q[:101, 0])) <= tolerance


def test_integrate_ends_at_the_time_asked_to_the_bit():
    """integrate(1.7) from t = 1 with h = 0.01 is 70 steps, and 1 + 70·0.01 rounds to
    1.7000000000000002: the last step is 1.7 − t₆₉ (h to round-off), so the simulation stands
    at 1.7 itself."""
    sim = oscillator().simulation()
    sim.integrate(1.0)
    assert 1.0 + 70 * 0.01 != 1.7
    stretch = sim.integrate(1.7)
    assert sim.t == 1.7 and stretch.t[-1] == 1.7 and len(stretch.t) == 71


def test_integrate_reaches_a_time_off_the_grid_exactly():
    """integrate(π) ends at π exactly with a shorter last step; the state is the closed-form
    oscillator's to the midpoint rule's O(h²) (h = 0.01: 1e-4 over a half period), and the
    energy ½(q² + p²), a quadratic invariant the midpoint rule keeps at any step size, is
    1/2 to round-off."""
    sim = oscillator().simulation()
    sim.integrate(math.pi)
    assert sim.t == math.pi
    assert abs(sim.q[0] + 1.0) < 1e-4 and abs(sim.p[0]) < 1e-4
    assert abs(0.5 * (sim.q[0] ** 2 + sim.p[0] ** 2) - 0.5) < 1e-13


def test_a_saved_simulation_continues_as_the_one_not_stopped(tmp_path):
    sim = oscillator().simulation()
    sim.integrate(0.77)
    path = tmp_path / "oscillator.sim"
    sim.save(path)
    loaded = marsden.Simulation.load(path)
    assert loaded.t == sim.t and loaded.steps == sim.steps
    assert loaded.q.tolist() == sim.q.tolist() and loaded.p.tolist() == sim.p.tolist()
    a, b = sim.integrate(3.3), loaded.integrate(3.3)
    assert a.q.tolist() == b.q.tolist() and a.p.tolist() == b.p.tolist()
    (tmp_path / "junk.sim").write_text("{}")
    with pytest.raises(marsden.ProblemError, match="not a saved simulation"):
        marsden.Simulation.load(tmp_path / "junk.sim")


def test_a_stop_event_leaves_the_simulation_at_its_step():
    """The pendulum released at 1.5 reaches θ = 0 at T/4 = 1.8252… (R7): integrate(5) stops
    there."""
    text = """
[system]
coordinates = ["theta"]
lagrangian = "0.5*theta_dot^2 + cos(theta)"
[initial]
q = [1.5]
v = [0.0]
[integrator]
h = 0.01
t_end = 10
[[events]]
name = "bottom"
when = "theta"
direction = "down"
action = "stop"
"""
    sim = marsden.Problem.from_toml(text).simulation()
    stretch = sim.integrate(5.0)
    assert stretch.status == "stopped by event bottom"
    assert 1.82 < sim.t < 1.84 and sim.q[0] <= 0.0 < sim.q[0] + 0.02


def test_what_cannot_be_stepped_is_refused():
    sim = oscillator().simulation()
    with pytest.raises(marsden.ProblemError, match="not after the current time"):
        sim.integrate(0.0)
    with pytest.raises(marsden.ProblemError, match="n must be a whole number"):
        sim.step(0)
    rigid = marsden.Problem(rigid_body={"inertia": [2.0, 1.0, 0.5]}, Pi0=[0.1, 1.0, 0.1],
                            method="trapezoid", h=0.01, steps=10)
    with pytest.raises(marsden.ProblemError, match="rigid body"):
        rigid.simulation()


def test_a_run_checkpoint_becomes_a_simulation(tmp_path):
    """A run that wrote checkpoints (every 150 steps of 400: the last at step 300) as a
    Simulation: it stands at the checkpoint's state and steps on to the run's own end state,
    bit for bit for the explicit trapezoid, to the Newton tolerance for the midpoint rule."""
    for method, tolerance in [("trapezoid", 0.0), ("midpoint", 1e-13)]:
        out = tmp_path / method
        whole = oscillator(method).solve(dir=str(out), checkpoint_every=150)
        sim = marsden.Simulation.from_checkpoint(out)
        assert sim.steps == 300 and abs(sim.t - 3.0) < 1e-12
        sim.step(100)
        assert abs(sim.t - whole.t[-1]) < 1e-12
        assert abs(sim.q[0] - whole.q[-1, 0]) <= tolerance
        assert abs(sim.p[0] - whole.p[-1, 0]) <= tolerance
    with pytest.raises(marsden.ProblemError, match="checkpoint"):
        marsden.Simulation.from_checkpoint(tmp_path / "nowhere")
