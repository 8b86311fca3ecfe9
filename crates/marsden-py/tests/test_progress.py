"""``solve(progress=True)`` does not flood a stream that is not a terminal (a log, a notebook,
a captured stream): at most one line per tenth of the run; a terminal gets one line redrawn in
place; a function gets every report."""

from __future__ import annotations

import contextlib
import io

import pytest

import marsden
from conftest import PENDULUM
from marsden._progress import Report

#: 200 000 steps: the run reports every 256 steps, about 780 times.
STEPS = 200_000


class Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_progress_on_a_captured_stream_is_at_most_one_line_per_tenth():
    captured = io.StringIO()
    with contextlib.redirect_stderr(captured):
        marsden.Problem(**PENDULUM, steps=STEPS).solve(every=STEPS, progress=True)
    lines = captured.getvalue().splitlines()
    assert 2 <= len(lines) <= 11, lines
    assert "\r" not in captured.getvalue()
    assert lines[-1].startswith(f"  step {STEPS}/{STEPS} (100.0 %)"), lines


def test_a_function_gets_every_report_and_the_last_says_done():
    calls = []
    marsden.Problem(**PENDULUM, steps=STEPS).solve(
        every=STEPS, progress=lambda step, total, elapsed, done: calls.append((step, total, done)))
    assert len(calls) > 100  # the flood the report above keeps off the stream
    assert calls[-1] == (STEPS, STEPS, True)
    assert all(not done for _, _, done in calls[:-1])
    assert [s for s, _, _ in calls] == sorted(s for s, _, _ in calls)


def test_an_exception_in_the_function_stops_the_run_and_is_raised():
    def fail(step, total, elapsed, done):
        raise ValueError(f"stop at {step}")

    with pytest.raises(ValueError, match="stop at"):
        marsden.Problem(**PENDULUM, steps=STEPS).solve(every=STEPS, progress=fail)


def test_the_report_on_a_terminal_redraws_one_line():
    stream = Terminal()
    report = Report(stream)
    for k in range(1, 1001):
        report(k * 100, 100_000, k * 1e-3, k == 1000)  # a second in all: about ten redraws
    text = stream.getvalue()
    assert text.count("\n") == 1 and text.endswith("(100.0 %), 1.0 s\n"), text
    assert 5 <= text.count("\r") <= 12, text


def test_the_report_elsewhere_says_where_a_stopped_run_ended():
    stream = io.StringIO()
    report = Report(stream)
    for k in range(1, 36):
        report(k * 100, 10_000, 0.0, False)
    report(3500, 10_000, 0.0, True)
    lines = stream.getvalue().splitlines()
    assert len(lines) == 5 and lines[-1].endswith("(stopped)"), lines
