"""``marsden.OptimalControl`` (an optimal control problem from keywords) and
``marsden.OptimalControlSolution``, the result of ``Problem.optimize()`` for a problem with an
``[optimal_control]`` table (discrete mechanics and optimal control, solved in Rust as by
``marsden optimize``)."""

from __future__ import annotations

import json
import tomllib
from typing import TYPE_CHECKING, Any, Dict, List, Mapping, Optional, Sequence

import numpy as np

from . import _keywords as kw
from . import _toml
from ._errors import ProblemError

if TYPE_CHECKING:
    from ._problem import Problem


class OptimalControlSolution:
    """An optimal (or, if the solver stopped early, the last) trajectory and its controls.

    - ``t`` (``N + 1``), ``q`` and ``p`` (``N + 1 × n``, one column per coordinate);
    - ``u`` (one column per control): ``N`` rows, ``u[k]`` acting on ``[t[k], t[k + 1]]``, for a
      rule with one control value per step (midpoint, trapezoid, the α rules, compositions);
      ``N σ`` rows, one per quadrature node, for ``gauss-<s>`` and ``lobatto-<s>``;
    - ``t_u``: the time of each row of ``u`` (``t[k]``, or ``t[k] + c_i h`` at the nodes);
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
        self.t_u: np.ndarray = fields["t_u"]
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
                f"{oc['iterations']} iterations, {len(self.t) - 1} steps, "
                f"controls {', '.join(self.controls)}>")


#: Sections of a problem that an optimal control problem does not use (its horizon, rule and
#: boundary data are the keywords of :class:`OptimalControl`).
_UNUSED = ("initial", "integrator", "sweep", "sensitivity", "analysis", "optimal_control")


class OptimalControl:
    """An optimal control problem (DMOC) on the system of a :class:`marsden.Problem`, from
    keywords: the ``[optimal_control]`` table of a problem file.

    The problem gives the system (Lagrangian, coordinates, parameters, symmetries, forces);
    ``controls`` names the controls and ``forces`` the controlled forces, one per coordinate,
    added to the problem's own. The problem's initial state and integrator settings are not
    used: ``start`` and ``end`` (``{"q": [...], "v": [...]}`` or ``"p"``, any component
    ``"free"``), ``t_end``, ``steps`` and ``method`` take their place::

        >>> pendulum = marsden.Problem("0.5*theta_dot^2 + cos(theta)", coordinates="theta",
        ...                            q0=[0.0], v0=[0.0])
        >>> swing_up = marsden.OptimalControl(
        ...     pendulum, controls=["u"], forces=["u"], cost="0.5*u^2", t_end=6.0, steps=100,
        ...     start={"q": [0.0], "v": [0.0]}, end={"q": [math.pi], "v": [0.0]},
        ...     bounds={"u": [-1.5, 1.5]}, guess="line")
        >>> s = swing_up.solve()
        >>> s.status, s.cost, s.u[:, 0]

    ``path`` lists inequalities ``g(t, q, q̇, u) <= 0`` (``["x - 1/9"]``: a state constraint),
    imposed at each step's midpoint (at each quadrature node for ``gauss-<s>``/``lobatto-<s>``);
    ``summary["optimal_control"]["path"]`` reports each one's largest value, active points and
    largest multiplier.

    ``method`` is any rule but ``exact`` (``gauss-<s>`` and ``lobatto-<s>`` take one control per
    quadrature node and converge with their own order). Bad input raises
    :class:`marsden.ProblemError` with the message of ``marsden optimize``; ``toml`` is the
    problem file it solves.
    """

    def __init__(
        self,
        problem: "Problem",
        cost: kw.Expression,
        t_end: float,
        steps: int,
        start: Mapping[str, Sequence[Any]],
        end: Mapping[str, Sequence[Any]],
        *,
        controls: Optional[Sequence[str]] = None,
        forces: Optional[Sequence[kw.Expression]] = None,
        final_cost: Optional[kw.Expression] = None,
        t0: Optional[float] = None,
        method: Optional[str] = None,
        bounds: Optional[Mapping[str, Sequence[float]]] = None,
        path: Optional[Sequence[kw.Expression]] = None,
        guess: Optional[str] = None,
        tolerance: Optional[float] = None,
        constraint_tolerance: Optional[float] = None,
        max_iterations: Optional[int] = None,
    ) -> None:
        from ._problem import Problem

        tables = tomllib.loads(problem.toml)
        system = dict(tables.get("system", {}))
        if controls is not None:
            system["controls"] = kw.names(controls, "controls")
        if forces is not None:
            system["forces"] = _added_forces(system.get("forces"), forces)
        table: Dict[str, Any] = {
            "cost": kw.expression(cost, "cost"),
            "t_end": float(t_end),
            "steps": int(steps),
            "start": _end("start", start),
            "end": _end("end", end),
        }
        optional = {
            "final_cost": kw.maybe(lambda c: kw.expression(c, "final_cost"), final_cost),
            "path": kw.maybe(lambda gs: [kw.expression(g, f"path[{i}]") for i, g in enumerate(gs)],
                             path),
            "t0": kw.maybe(float, t0),
            "method": method,
            "guess": guess,
            "tolerance": kw.maybe(float, tolerance),
            "constraint_tolerance": kw.maybe(float, constraint_tolerance),
            "max_iterations": kw.maybe(int, max_iterations),
        }
        table.update({k: v for k, v in optional.items() if v is not None})
        document = {"system": system, "optimal_control": table}
        if bounds:
            document["optimal_control.bounds"] = {
                str(name): [float(lo), float(hi)] for name, (lo, hi) in bounds.items()}
        rest = {k: v for k, v in tables.items() if k not in ("system", *_UNUSED)}
        document.update(rest)
        self.problem: Problem = Problem.from_toml(_document(document), "<OptimalControl>")

    @property
    def toml(self) -> str:
        """The problem-file text (``marsden optimize`` solves it the same way)."""
        return self.problem.toml

    def solve(self) -> OptimalControlSolution:
        """Solves the problem (see :meth:`marsden.Problem.optimize`)."""
        return self.problem.optimize()


def _document(tables: Mapping[str, Mapping[str, Any]]) -> str:
    """``tables`` as problem text; a dotted name (``optimal_control.bounds``) is a sub-table."""
    lines = []
    for name, entries in tables.items():
        header = ".".join(_toml.key(part) for part in name.split("."))
        lines.append(f"[{header}]")
        lines += [f"{_toml.key(k)} = {_toml.value(v)}" for k, v in entries.items()]
    return "\n".join(lines) + "\n"


def _added_forces(existing: Optional[Sequence[str]], forces: Sequence[kw.Expression]) -> List[str]:
    """The controlled forces, each added to the problem's own force on that coordinate."""
    if isinstance(forces, str) or not hasattr(forces, "__iter__"):
        forces = [forces]
    texts = [kw.expression(f, f"forces[{i}]") for i, f in enumerate(forces)]
    if existing is None:
        return texts
    if len(existing) != len(texts):
        raise ProblemError(f"error: forces: {len(texts)} controlled forces for a problem with "
                           f"{len(existing)} forces (one per coordinate)")
    return [f"({a}) + ({b})" for a, b in zip(existing, texts)]


def _end(name: str, values: Mapping[str, Sequence[Any]]) -> Dict[str, List[Any]]:
    """``{"q": [...], "v" or "p": [...]}`` with ``"free"`` components kept as text."""
    if not isinstance(values, Mapping):
        raise ProblemError(f"error: {name}: expected a mapping such as "
                           f"{{'q': [0.0], 'v': [0.0]}}, got {values!r}")
    return {str(k): [c if isinstance(c, str) else float(c) for c in v]
            for k, v in values.items()}
