"""A problem is checked and its initial state prepared once, when it is made: ``solve()`` runs
the checked problem (the overrides applied to a copy of it), with the bits and the messages of
the text read again."""

from __future__ import annotations

import json

import numpy as np
import pytest

import marsden
from marsden import _native
from conftest import PENDULUM

ARRAYS = ("t", "q", "p", "v", "energy")


def same_bits(a: marsden.Solution, b: marsden.Solution) -> bool:
    return all(getattr(a, k).tobytes() == getattr(b, k).tobytes() for k in ARRAYS)


def message(call) -> str:
    with pytest.raises(marsden.ProblemError) as e:
        call()
    return str(e.value)


def test_solved_twice_the_same_bits_as_the_text_read_again():
    problem = marsden.Problem(**PENDULUM, steps=200)
    first, second = problem.solve(), problem.solve()
    assert same_bits(first, second)
    again = marsden.Solution(_native.solve(problem.toml, "<python>"))
    assert same_bits(first, again)


def test_the_problem_is_not_read_again_by_solve(tmp_path, monkeypatch):
    """The N-body file was read when the problem was checked: gone since, the run needs it not."""
    (tmp_path / "two.txt").write_text("2\n1.0 1 0 0 0 0.5 0\n1.0 -1 0 0 0 -0.5 0\n")
    monkeypatch.chdir(tmp_path)
    problem = marsden.Problem(builtin="nbody", bodies_file="two.txt", h=0.01, steps=10)
    (tmp_path / "two.txt").unlink()
    solution = problem.solve()
    assert solution.q[0].tolist()[:3] == [1.0, 0.0, 0.0]
    assert problem.simulation().step(3).q.shape[0] == 4


def test_every_overrides_the_checked_problem_alone():
    problem = marsden.Problem(**PENDULUM, steps=20)
    thinned = problem.solve(every=7)
    assert thinned.t.tolist() == pytest.approx([0.0, 0.35, 0.7, 1.0])
    assert same_bits(thinned, marsden.Solution(_native.solve(problem.toml, "<python>", 7)))
    assert len(problem.solve().t) == 21


def test_dir_and_checkpoints_write_the_files_of_the_run(tmp_path):
    problem = marsden.Problem(**PENDULUM, steps=20)
    solution = problem.solve(dir=str(tmp_path / "run"), checkpoint_every=5)
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert summary["status"] == "completed"
    assert (tmp_path / "run" / "trajectory.csv").exists()
    assert same_bits(solution, problem.solve())


@pytest.mark.parametrize("overrides", [
    {"every": 0},
    {"checkpoint_every": 5},
    {"checkpoint_every": 0, "dir": "out-never-written"},
])
def test_bad_overrides_give_the_messages_of_the_text(overrides):
    problem = marsden.Problem.from_toml(marsden.Problem(**PENDULUM, steps=20).toml, "<python>")
    checked = message(lambda: problem.solve(**overrides))
    text = message(lambda: _native.solve(problem.toml, "<python>", **overrides))
    assert checked == text
    assert "must be at least 1" in checked or "give `dir`" in checked


def test_checkpoints_refused_for_a_run_that_cannot_resume(tmp_path):
    keywords = marsden.Problem(builtin="pendulum", q0=[1.0], v0=[0.0], h=0.1, steps=10,
                               method="exact")
    problem = marsden.Problem.from_toml(keywords.toml, "<python>")
    out = str(tmp_path / "exact")
    checked = message(lambda: problem.solve(dir=out, checkpoint_every=2))
    assert checked.startswith("error: checkpoints are not available for the method `exact`")
    assert checked == message(
        lambda: _native.solve(problem.toml, "<python>", dir=out, checkpoint_every=2))
