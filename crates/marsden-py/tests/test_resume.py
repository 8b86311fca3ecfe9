"""Checkpoints from Python: ``Problem.solve(dir=..., checkpoint_every=...)`` writes them, a
process killed with SIGKILL part-way is continued by ``marsden.resume(dir)``, and the files it
leaves are those of the uninterrupted run byte for byte."""

from __future__ import annotations

import json
import os
import pathlib
import signal
import subprocess
import sys
import textwrap
import time

import pytest

import marsden

TEXT = textwrap.dedent("""\
    [system]
    builtin = "pendulum"
    [initial]
    q = [1.0]
    v = [0.0]
    [integrator]
    method = "midpoint"
    h = 0.01
    steps = 1500000
    [output]
    every = 500
    plots = false
    """)


def test_a_killed_solve_resumes_to_the_uninterrupted_files(tmp_path: pathlib.Path) -> None:
    whole = tmp_path / "whole"
    s = marsden.Problem.from_toml(TEXT).solve(dir=str(whole), checkpoint_every=100_000)
    assert s.ok and (whole / "checkpoint.bin").exists()
    killed = tmp_path / "killed"
    script = (f"import marsden; marsden.Problem.from_toml({TEXT!r}).solve("
              f"dir={str(killed)!r}, checkpoint_every=100_000)")
    child = subprocess.Popen([sys.executable, "-c", script])
    deadline = time.time() + 60
    while not (killed / "checkpoint.bin").exists() and time.time() < deadline:
        time.sleep(0.005)
    running = child.poll() is None
    os.kill(child.pid, signal.SIGKILL)
    child.wait()
    summary = marsden.resume(killed)
    assert summary["status"] == "completed" and summary["steps"] == 1_500_000
    assert (killed / "trajectory.csv").read_bytes() == (whole / "trajectory.csv").read_bytes()
    assert (killed / "checkpoint.bin").read_bytes() == (whole / "checkpoint.bin").read_bytes()
    # The solution in memory of the whole run is what the files hold.
    assert summary["final_state"]["q"] == list(s.q[-1])
    assert running, "the kill came after the run had ended: lengthen the run"


def test_checkpoints_need_a_directory_and_resume_needs_a_checkpoint(tmp_path: pathlib.Path) -> None:
    with pytest.raises(marsden.ProblemError, match="give `dir` with `checkpoint_every`"):
        marsden.Problem.from_toml(TEXT).solve(checkpoint_every=10)
    with pytest.raises(marsden.ProblemError, match="there is no checkpoint"):
        marsden.resume(tmp_path)


SWEEP = textwrap.dedent("""\
    [system]
    builtin = "pendulum"
    [initial]
    q = [1.0]
    v = [0.0]
    [integrator]
    method = "midpoint"
    h = 0.01
    steps = 300000
    [output]
    plots = false
    checkpoint_every = 1
    [sweep]
    initial = "q[0]"
    range = { start = 0.2, stop = 2.4, count = 12 }
    """)


def test_a_killed_sweep_of_the_command_resumes_from_python(tmp_path: pathlib.Path, cli: str) -> None:
    """A sweep run by ``marsden run`` and killed part-way: ``marsden.resume`` keeps the members
    in its table, runs the others, and the table is the uninterrupted sweep's byte for byte."""
    problem = tmp_path / "sweep.toml"
    problem.write_text(SWEEP)
    whole, killed = tmp_path / "whole", tmp_path / "killed"
    args = ["-q", "--no-progress", "--threads", "2"]
    subprocess.run([cli, "run", str(problem), "--out", str(whole), *args], check=True)
    child = subprocess.Popen([cli, "run", str(problem), "--out", str(killed), *args])
    deadline = time.time() + 60
    while not (killed / "sweep-checkpoint.bin").exists() and time.time() < deadline:
        time.sleep(0.005)
    running = child.poll() is None
    os.kill(child.pid, signal.SIGKILL)
    child.wait()
    summary = marsden.resume(killed)
    assert summary["kind"] == "sweep" and summary["status"] == "completed"
    assert summary["members_run"] == 12
    assert (killed / "sweep.csv").read_bytes() == (whole / "sweep.csv").read_bytes()
    assert running, "the kill came after the sweep had ended: lengthen the members"


SENSITIVITY = TEXT.replace("steps = 1500000", "steps = 300000").replace(
    "[output]", "[sensitivity]\ninitial = true\n[output]")


def test_a_solve_killed_in_its_tangent_run_resumes_to_the_same_jacobians(
        tmp_path: pathlib.Path) -> None:
    """``[sensitivity]``: a process killed while its tangent run goes (after the tangent run's
    first checkpoint) is continued by ``marsden.resume``; ``sensitivity.csv`` is the
    uninterrupted run's byte for byte, and its final Jacobian is the one the whole run gave."""
    whole = tmp_path / "whole"
    s = marsden.Problem.from_toml(SENSITIVITY).solve(dir=str(whole), checkpoint_every=20_000)
    assert s.ok and (whole / "sensitivity-checkpoint.bin").exists()
    killed = tmp_path / "killed"
    script = (f"import marsden; marsden.Problem.from_toml({SENSITIVITY!r}).solve("
              f"dir={str(killed)!r}, checkpoint_every=20_000)")
    child = subprocess.Popen([sys.executable, "-c", script])
    deadline = time.time() + 60
    while not (killed / "sensitivity-checkpoint.bin").exists() and time.time() < deadline:
        time.sleep(0.005)
    running = child.poll() is None
    os.kill(child.pid, signal.SIGKILL)
    child.wait()
    summary = marsden.resume(killed)
    assert summary["status"] == "completed"
    assert summary["sensitivity"]["error"] is None
    assert (killed / "sensitivity.csv").read_bytes() == (whole / "sensitivity.csv").read_bytes()
    whole_summary = json.loads((whole / "summary.json").read_text())
    assert summary["sensitivity"]["final"] == whole_summary["sensitivity"]["final"]
    assert running, "the kill came after the run had ended: lengthen the run"
