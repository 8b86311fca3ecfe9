"""The exceptions of marsden: bad problems and failed simulations."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ._native import ProblemError

if TYPE_CHECKING:
    from ._solution import Solution

__all__ = ["ProblemError", "SimulationError"]

ProblemError.__module__ = "marsden"


class SimulationError(RuntimeError):
    """A run that failed part-way (a Newton iteration that did not converge, a state that
    stopped being finite, ...).

    ``.solution`` holds the trajectory up to the failure: every stored sample before it, all
    finite, and ``.solution.summary`` as ``summary.json`` would have it (status ``"failed"``).
    """

    def __init__(self, message: str, solution: "Solution") -> None:
        super().__init__(message)
        self.solution = solution

    def __reduce__(self):  # picklable across processes (executors)
        return (SimulationError, (str(self), self.solution))
