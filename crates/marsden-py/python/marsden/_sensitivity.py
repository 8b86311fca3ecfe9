"""``marsden.Sensitivity``: derivatives of a run with respect to its initial state and its
parameters, and the ``[sensitivity]`` table that asks for them."""

from __future__ import annotations

from typing import Any, Dict, List, Mapping, Optional, Sequence, Union

import numpy as np

from . import _toml
from ._errors import ProblemError

#: What ``Problem.solve(sensitivity=...)`` takes: ``True`` (the initial state), parameter
#: names, or ``{"initial": bool, "parameters": [names]}``.
Request = Union[bool, Sequence[str], Mapping[str, Any]]


class Sensitivity:
    """The Jacobians ``∂(q_k, p_k)/∂(columns)`` of a run, from a tangent run beside it (the
    implicit function theorem on each converged step, not differences of runs).

    - ``rows``: ``q_<coordinate>`` then ``p_<coordinate>`` (``2n`` names);
    - ``columns``: ``q0_<coordinate>``, ``p0_<coordinate>`` (when the initial state was
      asked for), then the parameter names;
    - ``final``: the Jacobian at the last step (``2n × columns``);
    - ``t`` and ``jacobians``: the Jacobians at the stored steps (``samples × 2n × columns``,
      the same stride as the solution's samples);
    - ``note``: how to read them, when that needs saying (constrained runs: only their action
      on tangent vectors of ``T*N`` is the derivative of the run).

    >>> s = pendulum.solve(sensitivity=["g"])
    >>> s.sensitivity.final[:, s.sensitivity.columns.index("g")]   # ∂(θ, p_θ)/∂g at the end
    """

    def __init__(self, block: Dict[str, Any], arrays: Dict[str, Any]) -> None:
        self.rows: List[str] = list(block["rows"])
        self.columns: List[str] = list(block["columns"])
        self.final: np.ndarray = np.array(block["final"], dtype=float).reshape(
            len(self.rows), len(self.columns))
        self.t: np.ndarray = arrays["t"]
        self.jacobians: np.ndarray = arrays["jacobians"]
        self.note: Optional[str] = block.get("note")

    def column(self, name: str) -> np.ndarray:
        """The final Jacobian's column ``name`` (``∂(q, p)/∂name`` at the last step)."""
        try:
            return self.final[:, self.columns.index(name)]
        except ValueError:
            raise KeyError(f"no column {name!r}; the columns are {self.columns}") from None

    def __repr__(self) -> str:
        return (f"Sensitivity(rows={self.rows}, columns={self.columns}, "
                f"{len(self.t)} stored Jacobians)")


def table(request: Request) -> str:
    """The ``[sensitivity]`` table of ``request`` (checked with the rest of the problem by the
    native layer); a request of the wrong type raises :class:`ProblemError`."""
    initial = False
    parameters: List[str] = []
    if isinstance(request, bool):
        initial = request
    elif isinstance(request, Mapping):
        unknown = set(request) - {"initial", "parameters"}
        if unknown:
            raise ProblemError(f"sensitivity: unknown key(s) {sorted(unknown)}; "
                               "the keys are 'initial' and 'parameters'")
        initial = bool(request.get("initial", False))
        parameters = _names(request.get("parameters", []))
    else:
        parameters = _names(request)
    entries = [("initial", "true" if initial else None),
               ("parameters", _toml.strings(parameters) if parameters else None)]
    return "\n".join([""] + _toml.table("sensitivity", entries)) + "\n"


def _names(values: Any) -> List[str]:
    if isinstance(values, str) or not isinstance(values, Sequence):
        raise ProblemError("sensitivity: parameters are a list of names, e.g. ['g', 'l'] "
                           f"(got {values!r})")
    if not all(isinstance(v, str) for v in values):
        raise ProblemError(f"sensitivity: parameter names must be strings (got {list(values)!r})")
    return list(values)
