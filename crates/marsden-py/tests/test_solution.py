"""What a Solution holds when the run has no energy (a discrete Lagrangian): ``None``, no
column, and a plot of what exists; and the package's version."""

from __future__ import annotations

import re

import numpy as np
import pytest

import marsden
from conftest import EXAMPLES, ROOT


def discrete() -> marsden.Solution:
    return marsden.Problem.load(EXAMPLES / "discrete_oscillator.toml").solve()


def test_a_discrete_lagrangian_solution_has_no_energy_but_its_samples():
    s = discrete()
    assert s.energy is None
    assert s.q.shape == (201, 1) and len(s.t) == 201
    # R1: the midpoint L_d conserves H = (p² + q²)/2 exactly (a quadratic invariant): the
    # samples carry it even though the run reports no energy.
    h = 0.5 * (s.p[:, 0] ** 2 + s.q[:, 0] ** 2)
    assert np.max(np.abs(h - 0.5)) < 1e-13
    assert "samples" in repr(s)


def test_to_pandas_leaves_out_the_energy_column_of_a_discrete_lagrangian():
    pd = pytest.importorskip("pandas")
    frame = discrete().to_pandas()
    assert isinstance(frame, pd.DataFrame) and len(frame) == 201
    assert list(frame.columns) == ["t", "x", "p_x", "v_x"]


def test_plot_draws_a_discrete_lagrangian_solution():
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    figure = discrete().plot()
    phase, energy = figure.axes
    assert len(phase.lines) == 1 and not energy.lines
    assert "no energy" in energy.get_title()


def test_plot_of_a_discrete_lagrangian_with_a_symmetry_draws_its_momentum_map():
    """A free particle's L_d = h·½((x₁ − x₀)/h)² is translation invariant: J = p, constant."""
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    s = marsden.Problem(discrete_lagrangian="h*0.5*((x_1 - x_0)/h)^2", coordinates="x",
                        translation="x", q0=[0.0], p0=[0.5], h=0.1, steps=10).solve()
    assert s.energy is None and np.all(s.momenta["Px"] == 0.5)
    drift = s.plot().axes[1]
    assert [line.get_label() for line in drift.lines] == ["J_Px"]


def test_plot_of_an_ordinary_run_draws_the_energy_error():
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    s = marsden.Problem.load(EXAMPLES / "pendulum.toml").solve(every=1000)
    figure = s.plot()
    assert len(figure.axes[1].lines) == 1 and figure.axes[1].get_title() == "energy error"


def test_version_is_the_cargo_workspace_version():
    cargo = (ROOT / "Cargo.toml").read_text()
    workspace = re.search(r"\[workspace\.package\][^\[]*?\nversion = \"([^\"]+)\"", cargo)
    assert workspace, "no version in [workspace.package]"
    assert marsden.__version__ == workspace.group(1)
