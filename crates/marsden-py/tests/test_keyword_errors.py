"""Mistakes in a problem built from keywords are reported in keyword terms (``give steps= or
t_end=``), pointing at the keyword, and inside an expression at the fault; problem text keeps
the problem-file messages with their caret. A sweep is not solved as one run, and an N-body
file is looked for where the message says."""

from __future__ import annotations

import pytest

import marsden
from conftest import EXAMPLES, PENDULUM

BASE = dict(lagrangian="0.5*x_dot^2 - 0.5*x^2", coordinates=["x"], q0=[1.0], v0=[0.0],
            h=0.1, steps=10)


def message(**kwargs) -> str:
    with pytest.raises(marsden.ProblemError) as info:
        marsden.Problem(**kwargs)
    return str(info.value)


def without(*keys: str) -> dict:
    return {k: v for k, v in BASE.items() if k not in keys}


def speaks_keywords(text: str) -> None:
    """No TOML table names, no line of the generated text."""
    for toml in ("[integrator]", "[initial]", "[system]", "<python>:"):
        assert toml not in text, text


def test_missing_steps_and_t_end_says_give_steps_or_t_end():
    text = message(**without("steps"))
    assert "give steps= or t_end=" in text, text
    speaks_keywords(text)


def test_steps_and_t_end_both():
    text = message(**BASE, t_end=1.0)
    assert "give either steps= or t_end=, not both" in text, text
    speaks_keywords(text)




def test_missing_h_says_give_h():
    text = message(**without("h"))
    assert "give the time step h=" in text, text
    speaks_keywords(text)


def test_missing_q0_says_give_q0():
    text = message(**without("q0"))
    assert "q0=" in text, text
    speaks_keywords(text)


def test_v0_and_p0_both():
    text = message(**BASE, p0=[0.0])
    assert "give either v0= or p0=, not both" in text, text
    assert "--> in p0=" in text, text
    speaks_keywords(text)


def test_wrong_length_names_the_keyword():
    text = message(**{**BASE, "q0": [1.0, 2.0]})
    assert "q0 has 2 values, but the system has 1" in text, text
    speaks_keywords(text)


def test_unknown_method_points_at_method_with_the_suggestion():
    text = message(**BASE, method="midpiont")
    assert "unknown method" in text and "--> in method=" in text, text
    assert "did you mean `midpoint`?" in text, text
    speaks_keywords(text)


def test_no_system_names_the_keywords_to_give():
    text = message(coordinates=["x"], q0=[1.0], v0=[0.0], h=0.1, steps=10)
    assert "give lagrangian=, builtin=" in text, text
    speaks_keywords(text)


def test_an_unknown_name_is_pointed_at_inside_the_expression():
    text = message(**{**PENDULUM, "lagrangian": "0.5*m*l^2*theta_dot^2 + m*gg*l*cos(theta)"},
                   steps=10)
    assert "unknown name `gg`" in text and "known names: g, l, m" in text, text
    lines = text.splitlines()
    at = lines.index("   | 0.5*m*l^2*theta_dot^2 + m*gg*l*cos(theta)")
    assert lines[at - 2] == "  --> in lagrangian="
    assert lines[at + 1] == "   | " + " " * 26 + "^^", text
    speaks_keywords(text)


def test_a_force_is_pointed_at_by_its_index():
    text = message(**BASE, forces=["-c*x_dot"])
    assert "in forces[0]: unknown name `c`" in text, text
    assert "--> in forces[0]=" in text and "   | -c*x_dot" in text, text
    assert "   |  ^" in text, text


def test_discrete_lagrangian_with_a_method_says_leave_out_method():
    text = message(discrete_lagrangian="h*((x_1 - x_0)/h)^2/2", coordinates="x", q0=[1.0],
                   p0=[0.0], method="midpoint", h=0.1, steps=10)
    assert "`method` cannot be used with `discrete_lagrangian`" in text, text
    assert "leave out method=" in text, text
    speaks_keywords(text)
    text = message(discrete_lagrangian="h*((x_1 - x_0)/h)^2/2", coordinates="x", q0=[1.0],
                   v0=[0.0], h=0.1, steps=10)
    assert "`v0` cannot be used with `discrete_lagrangian`" in text, text
    assert "give the initial momenta p0=[...]" in text and "--> in v0=" in text, text


def test_problem_text_keeps_the_caret_and_the_toml_terms():
    text = "[system]\nbuiltin = \"pendulum\"\n[initial]\nq = [1.0]\nv = [0.0]\n" \
           "[integrator]\nh = 0.1\n"
    with pytest.raises(marsden.ProblemError) as info:
        marsden.Problem.from_toml(text, "cell.toml")
    said = str(info.value)
    assert "[integrator] needs the length of the run" in said and "cell.toml:6:1" in said, said


def test_solving_a_sweep_file_says_to_run_the_sweep():
    problem = marsden.Problem.load(EXAMPLES / "pendulum_sweep.toml")
    with pytest.raises(marsden.ProblemError) as info:
        problem.solve()
    assert "sweep()" in str(info.value), str(info.value)


def test_the_sweep_method_runs_every_member_of_the_file():
    problem = marsden.Problem.load(EXAMPLES / "pendulum_sweep.toml")
    label, members = problem._info["sweep"]
    results = problem.sweep(every=1000)
    assert len(results) == len(members) > 1
    assert all(isinstance(r, marsden.Solution) and r.ok for r in results)


BODIES = "2\n1.0 1 0 0 0 0.5 0\n1.0 -1 0 0 0 -0.5 0\n"
NBODY = "[system]\nbuiltin = \"nbody\"\n[initial]\nfile = \"two.txt\"\n" \
        "[integrator]\nh = 0.01\nsteps = 10\n"


def test_load_resolves_the_n_body_file_relative_to_the_problem_file(tmp_path, monkeypatch):
    (tmp_path / "data").mkdir()
    (tmp_path / "data" / "two.txt").write_text(BODIES)
    (tmp_path / "data" / "p.toml").write_text(NBODY)
    monkeypatch.chdir(tmp_path)  # not the file's directory
    solution = marsden.Problem.load("data/p.toml").solve()
    assert solution.q[0, :3].tolist() == [1.0, 0.0, 0.0]


def test_from_toml_says_the_n_body_file_is_relative_to_the_working_directory(tmp_path,
                                                                            monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(marsden.ProblemError) as info:
        marsden.Problem.from_toml(NBODY)
    said = str(info.value)
    assert "relative to the working directory" in said, said
    assert "relative to the problem file" not in said, said
    (tmp_path / "two.txt").write_text(BODIES)
    assert marsden.Problem.from_toml(NBODY).solve().q.shape == (11, 6)
