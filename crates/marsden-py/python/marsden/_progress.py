"""``solve(progress=True)``: a progress report on ``sys.stderr`` that suits the stream.

The run calls back every few hundred steps. On a terminal the report is one line overwritten
in place (``\\r``), redrawn at most ten times a second; anywhere else (a log file, a notebook,
a captured stream) overwriting does not work and every call would be a line of its own, so
there it is one line per tenth of the run and one at the end: at most eleven lines however
long the run.
"""

from __future__ import annotations

import sys
from typing import Any, Callable, Optional, TextIO, Union

#: What ``solve(progress=...)`` takes: ``True`` for this report, or a function called as
#: ``f(step, total, elapsed_seconds, done)``.
Request = Union[bool, Callable[[int, int, float, bool], Any]]

#: Least time between two redraws on a terminal, in seconds.
REDRAW = 0.1


class Report:
    """Progress lines on ``stream`` (default ``sys.stderr`` when the report is made)."""

    def __init__(self, stream: Optional[TextIO] = None) -> None:
        self.stream: TextIO = sys.stderr if stream is None else stream
        self.terminal = _isatty(self.stream)
        self.last_tenth = -1
        self.last_redraw = -REDRAW

    def __call__(self, step: int, total: int, elapsed: float, done: bool) -> None:
        fraction = 1.0 if total == 0 else step / total
        text = f"  step {step}/{total} ({100.0 * fraction:5.1f} %), {elapsed:.1f} s"
        if self.terminal:
            if done or elapsed - self.last_redraw >= REDRAW:
                self.last_redraw = elapsed
                self.stream.write("\r" + text + ("\n" if done else ""))
                self.stream.flush()
            return
        tenth = int(10 * fraction)
        if tenth > self.last_tenth or done:
            if done and tenth == self.last_tenth and step == total:
                return  # the line of the last tenth already said it
            self.last_tenth = tenth
            self.stream.write(text + ("" if not done or step == total else " (stopped)") + "\n")
            self.stream.flush()


def callback(progress: Request) -> Optional[Callable[[int, int, float, bool], Any]]:
    """The function the run calls back, or ``None`` for no report."""
    if callable(progress):
        return progress
    return Report() if progress else None


def _isatty(stream: Any) -> bool:
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError, OSError):  # closed, or not a file
        return False
