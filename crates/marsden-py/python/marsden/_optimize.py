"""``marsden.OptimalControlSolution``: the result of ``Problem.optimize()`` for a problem with
an ``[optimal_control]`` table (discrete mechanics and optimal control, solved in Rust as by
``marsden optimize``)."""

from __future__ import annotations

import json
from typing import Any, Dict, List

import numpy as np


class OptimalControlSolution:
    """An optimal (or, if the solver stopped early, the last) trajectory and its controls.

    - ``t`` (``N + 1``), ``q`` and ``p`` (``N + 1 × n``, one column per coordinate);
    - ``u`` (``N × m``, one column per control; ``u[k]`` acts on ``[t[k], t[k + 1]]``);
    - ``cost``: the discrete cost at the returned iterate;
    - ``status``: ``"converged"``, ``"failed"``, ``"infeasible"`` or ``"iteration limit"``;
    - ``summary``: the dictionary ``marsden optimize`` writes as ``summary.json`` (its
      ``"optimal_control"`` entry has the iterations, KKT residual, constraint violation,
      Noether balance and replay defect).

    >>> s = marsden.Problem.load("examples/pendulum_swing_up.toml").optimize()
    >>> s.status, s.cost, s.u[:, 0]
    """

    def __init__(self, fields: Dict[str, Any]) -> None:
        self.coordinates: List[str] = list(fields["coordinates"])
        self.controls: List[str] = list(fields["controls"])
        self.t: np.ndarray = fields["t"]
        self.q: np.ndarray = fields["q"]
        self.p: np.ndarray = fields["p"]
        self.u: np.ndarray = fields["u"]
        self.cost: float = float(fields["cost"])
        self.status: str = fields["status"]
        self.summary: Dict[str, Any] = json.loads(fields["summary"])

    @property
    def converged(self) -> bool:
        """Whether the solver converged."""
        return self.status == "converged"

    def __repr__(self) -> str:
        oc = self.summary["optimal_control"]
        return (f"<OptimalControlSolution {self.status}: cost {self.cost:.6g} after "
                f"{oc['iterations']} iterations, {len(self.u)} steps, "
                f"controls {', '.join(self.controls)}>")
