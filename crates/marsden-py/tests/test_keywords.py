"""Every key of a problem file has its keyword in ``Problem(...)``, and each keyword takes
effect: a solve (or the ``marsden`` command on the generated file) shows it. Numbers are
expressions, and one coordinate may be given as a string."""

from __future__ import annotations

import json
import subprocess

import numpy as np
import pytest

import marsden
from conftest import EXAMPLES, PENDULUM

#: R1's system (m = k = 1) as the midpoint rule's discrete Lagrangian, as
#: examples/discrete_oscillator.toml writes it.
MIDPOINT_LD = "h*(0.5*((x_1 - x_0)/h)^2 - 0.5*w^2*((x_0 + x_1)/2)^2)"


def oscillator(**kwargs) -> marsden.Problem:
    return marsden.Problem(**{**dict(lagrangian="0.5*x_dot^2 - 0.5*x^2", coordinates=["x"],
                                     q0=[1.0], p0=[0.0], h=0.1, steps=100), **kwargs})


def test_numbers_are_expressions_in_forces_generators_and_constraints():
    """A constant force F on a free particle (L = ½ẋ²): p_N = p_0 + N h F exactly for the
    midpoint rule's discrete Lagrange–d'Alembert forcing; the generator [1] of translations
    is the momentum map p, and a numeric generator in a symmetry list prints as it reads."""
    problem = marsden.Problem(lagrangian="0.5*x_dot^2", coordinates=["x"], forces=[1],
                              symmetries={"P": [1]}, q0=[0.0], p0=[0.0], h=0.1, steps=10)
    solution = problem.solve()
    assert solution.p[-1, 0] == pytest.approx(1.0, abs=1e-14)
    assert np.allclose(solution.momenta["P"], solution.p[:, 0], rtol=0, atol=0)
    floats = marsden.Problem(lagrangian="0.5*x_dot^2", coordinates=["x"], forces=[-0.5],
                             q0=[0.0], p0=[0.0], h=0.1, steps=10).solve()
    assert floats.p[-1, 0] == pytest.approx(-0.5, abs=1e-14)


def test_sympy_and_numpy_numbers_are_expressions():
    sp = pytest.importorskip("sympy")
    a = marsden.Problem(lagrangian="0.5*x_dot^2", coordinates=["x"],
                        forces=[sp.Rational(1, 2)], q0=[0.0], p0=[0.0], h=0.1, steps=10).solve()
    b = marsden.Problem(lagrangian="0.5*x_dot^2", coordinates=["x"], forces=[np.float64(0.5)],
                        q0=[0.0], p0=[0.0], h=0.1, steps=10).solve()
    assert a.p[-1, 0] == b.p[-1, 0] == pytest.approx(0.5, abs=1e-14)


def test_a_value_that_is_no_expression_names_its_keyword():
    with pytest.raises(marsden.ProblemError) as info:
        marsden.Problem(lagrangian="0.5*x_dot^2", coordinates=["x"], forces=[{"f": 1}],
                        q0=[0.0], p0=[0.0], h=0.1, steps=10)
    assert "forces[0]" in str(info.value) and "expected an expression" in str(info.value)


def test_a_single_string_is_one_coordinate():
    one = marsden.Problem(**{**PENDULUM, "coordinates": "theta"}, steps=10)
    assert one.coordinates == ["theta"]
    listed = marsden.Problem(**PENDULUM, steps=10)
    assert np.array_equal(one.solve().q, listed.solve().q)


def test_discrete_lagrangian_keyword_reproduces_the_midpoint_rule_r1():
    """R1: the midpoint L_d of the harmonic oscillator (m = k = 1, h = 0.1, q0 = 1, p0 = 0)
    has q_10 = 0.54100229460035897, p_10 = −0.84102111580931570 (closed form)."""
    solution = marsden.Problem(discrete_lagrangian=MIDPOINT_LD, coordinates="x",
                               parameters={"w": 1.0}, q0=[1.0], p0=[0.0], h=0.1,
                               steps=10).solve()
    assert abs(solution.q[-1, 0] - 0.54100229460035897) < 1e-12
    assert abs(solution.p[-1, 0] + 0.84102111580931570) < 1e-12


def test_every_step_monitors_the_steps_between_stored_samples():
    """The pendulum's energy error oscillates within each period: monitored at every step it
    reaches a larger maximum than at every 100th step alone."""
    sparse = marsden.Problem(**PENDULUM, steps=2000, every=100).solve()
    dense = marsden.Problem(**PENDULUM, steps=2000, every=100, every_step=True).solve()
    assert len(dense) == len(sparse) == 21
    assert np.array_equal(dense.q, sparse.q)
    assert (dense.summary["energy"]["max_rel_error"]
            > sparse.summary["energy"]["max_rel_error"])


def test_certify_reports_the_symplecticity_defect_r17():
    """R17: the step map of a variational integrator is symplectic; the certificate measures
    its defect ‖DΦᵀ J DΦ − J‖ (relative), at round-off for the midpoint rule."""
    plain = marsden.Problem(**PENDULUM, steps=100).solve()
    certified = marsden.Problem(**PENDULUM, steps=100, certify=True).solve()
    assert "certificate" not in plain.summary
    symplecticity = certified.summary["certificate"]["symplecticity"]
    assert symplecticity["expected_symplectic"] is True
    assert max(symplecticity["start"], symplecticity["end"]) < 1e-13, symplecticity


def test_rotation_and_translation_name_the_momentum_maps():
    """Kepler (R10, e = 0.6): L_z = 0.8 from `rotation="z"`, the same series as the written
    generator; a translation's momentum map is p_x."""
    common = dict(q0=[0.4, 0.0], p0=[0.0, 2.0], h=0.01, steps=200)
    named = marsden.Problem.builtin("kepler", rotation="z", translation="x", **common).solve()
    written = marsden.Problem.builtin("kepler", symmetries={"Lz": ["-y", "x"]},
                                      **common).solve()
    assert sorted(named.momenta) == ["Lz", "Px"]
    assert np.array_equal(named.momenta["Lz"], written.momenta["Lz"])
    assert abs(named.momenta["Lz"][0] - 0.8) < 1e-15
    assert np.array_equal(named.momenta["Px"], named.p[:, 0])
    mapping = marsden.Problem.builtin("kepler", symmetries={"L": {"rotation": "z"}},
                                      **common).solve()
    assert np.array_equal(mapping.momenta["L"], written.momenta["Lz"])


def test_angles_t0_and_project_take_effect():
    s = marsden.Problem(**PENDULUM, steps=20, angles="theta", t0=1.0).solve()
    assert s.summary["output"]["angles"] == ["theta"]
    assert s.t[0] == 1.0 and s.t[-1] == pytest.approx(2.0)
    # A point off the circle x² + y² = 1, projected onto it before the run (R7's system).
    circle = dict(lagrangian="0.5*(x_dot^2 + y_dot^2) - y", coordinates=["x", "y"],
                  constraints=["x^2 + y^2 - 1"], q0=[0.1, -1.1], v0=[0.0, 0.0], h=0.05,
                  steps=20)
    with pytest.raises(marsden.ProblemError):
        marsden.Problem(**circle)
    projected = marsden.Problem(**circle, project=True).solve()
    assert abs(np.hypot(*projected.q[0]) - 1.0) < 1e-12


def test_angles_and_output_keywords_reach_the_file(cli, tmp_path):
    """`angles`, `output_dir`, `output_format`, `plots`: what `marsden run` writes."""
    out = tmp_path / "run"
    problem = marsden.Problem(**PENDULUM, steps=20, angles="theta", output_dir=out,
                              output_format="npy", plots=False, name="p")
    path = tmp_path / "p.toml"
    path.write_text(problem.toml)
    subprocess.run([cli, "run", str(path)], check=True, capture_output=True, cwd=tmp_path)
    summary = json.loads((out / "summary.json").read_text())
    assert summary["output"]["angles"] == ["theta"]
    assert not list(out.glob("*.png")) and list(out.glob("*.npy"))
    assert summary["final_state"]["q"] == problem.solve().q[-1].tolist()


def test_sensitivity_keyword_equals_the_solve_argument():
    a = marsden.Problem(**PENDULUM, steps=50, sensitivity=["g"]).solve()
    b = marsden.Problem(**PENDULUM, steps=50).solve(sensitivity=["g"])
    assert a.sensitivity is not None and np.array_equal(a.sensitivity.final, b.sensitivity.final)


def test_sweep_keyword_runs_with_the_sweep_method():
    problem = marsden.Problem(**PENDULUM, steps=100, sweep={"parameter": "l",
                                                             "values": [0.5, 1.0]})
    members = problem.sweep()
    alone = marsden.Problem(**{**PENDULUM, "parameters": {"m": 1.0, "l": 0.5, "g": 1.0}},
                            steps=100).solve()
    assert np.array_equal(members[0].q, alone.q)
    ranged = marsden.Problem(**PENDULUM, steps=10, sweep={
        "initial": "q[0]", "range": {"start": 0.1, "stop": 0.3, "count": 3}}).sweep()
    assert [s.q[0, 0] for s in ranged] == pytest.approx([0.1, 0.2, 0.3])


def test_bodies_file_keyword_reads_the_n_body_data(tmp_path, monkeypatch):
    """Two bodies of the benchmark format, relative to the working directory."""
    (tmp_path / "two.txt").write_text("2\n1.0 1 0 0 0 0.5 0\n1.0 -1 0 0 0 -0.5 0\n")
    monkeypatch.chdir(tmp_path)
    problem = marsden.Problem(builtin="nbody", bodies_file="two.txt", h=0.01, steps=10)
    solution = problem.solve()
    assert solution.q[0].tolist()[:3] == [1.0, 0.0, 0.0]


def test_the_keyword_table_covers_the_schema():
    """Each key of the problem-file schema (examples/ use them all) has a keyword."""
    import inspect

    keywords = set(inspect.signature(marsden.Problem).parameters)
    schema = {"name", "builtin", "coordinates", "parameters", "lagrangian", "hamiltonian",
              "discrete_lagrangian", "forces", "constraints", "symmetries", "rotation",
              "translation", "t0", "q0", "v0", "p0", "bodies_file", "project", "method", "h",
              "steps", "t_end", "tolerance", "max_iterations", "fast_paths", "compensated",
              "every", "angles", "output_dir", "output_format", "plots", "every_step",
              "certify", "sensitivity", "sweep"}
    assert schema <= keywords, schema - keywords
    assert EXAMPLES.is_dir()
