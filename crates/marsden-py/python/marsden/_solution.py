"""``marsden.Solution``: the stored samples of a run as NumPy arrays, and its summary."""

from __future__ import annotations

import json
from typing import Any, Dict, List, Optional

import numpy as np

from ._errors import SimulationError
from ._sensitivity import Sensitivity


class Solution:
    """The stored samples of a run (every ``every``-th step, the first and the last).

    Attributes (NumPy arrays, one row per stored sample):

    - ``t`` (``k``), ``q``, ``p``, ``v`` (``k × n``, one column per coordinate, in the order of
      ``coordinates``), ``energy`` (``⟨p, v⟩ − L``);
    - ``momenta``: momentum maps ``J`` by symmetry name (``solution.momenta["Lz"]``);
    - ``constraint_residual``: ``max_i |φ_i(q)|`` (``None`` without constraints), and
      ``constraint_velocity_residual``: the hidden constraint's ``max_i |(Dφ(q)·v)_i|``;
    - ``multipliers``: the Lagrange multipliers ``λ_i`` of the stored states, one column per
      constraint (``a = M⁻¹(… − Dφᵀλ)``; zero columns without constraints);
    - ``summary``: the dictionary ``marsden run`` writes as ``summary.json``;
    - ``status`` (``"completed"``, ``"failed"``), ``error`` (the failure's message),
      ``warnings``;
    - a rigid body's ``R`` (``k × 3 × 3``, body → space), ``Pi`` (``k × 3``, the body
      momentum ``Π = JΩ``) and ``quaternion`` (``k × 4``, ``[w, x, y, z]`` with ``w ≥ 0``);
      ``None`` for other systems;
    - jointed bodies' ``bodies``: by body name, a :class:`Body` with ``x``, ``p``, ``v``
      (``k × 3``: the centre of mass, its momentum and velocity), ``R`` (``k × 3 × 3``) and
      ``Pi`` (``k × 3``) (``solution.bodies["a"].R[-1]``); empty for other systems;
    - ``sensitivity``: the run's Jacobians (:class:`marsden.Sensitivity`) when they were asked
      for (``solve(sensitivity=...)`` or a ``[sensitivity]`` table), else ``None``;
    - ``observables``: the ``[output] observables`` at the stored samples, by name
      (``solution.observables["x2"]``, one value per row);
    - ``events``: the crossings located by the ``[[events]]``, by event name, each a dictionary
      ``{"t": (m,), "q": (m × n), "p": (m × n)}`` (``solution.events["x_up"]["q"][:, 1]``);
      a run stopped by an event has ``status`` ``"stopped by event <name>"``;
    - ``at_times``: the states at the requested ``times`` (``[output] times``), read off the
      interpolant of the step each lies in, as ``{"t": (k,), "q": (k × n), "p": (k × n),
      "observables": {name: (k,)}}`` (``solution.at_times["q"][:, 0]``); fewer than
      requested if the run ended first; ``None`` when no times were requested.

    >>> s = pendulum.solve(every=10)
    >>> s.t[-1], s.q[-1, 0], s.summary["energy"]["max_rel_error"]
    """

    def __init__(self, fields: Dict[str, Any]) -> None:
        self.coordinates: List[str] = list(fields["coordinates"])
        self.t: np.ndarray = fields["t"]
        self.q: np.ndarray = fields["q"]
        self.p: np.ndarray = fields["p"]
        self.v: np.ndarray = fields["v"]
        energy = fields["energy"]
        self.energy: Optional[np.ndarray] = (
            None if energy is None or (len(energy) == 0 and len(self.t) > 0) else energy)
        self.momenta: Dict[str, np.ndarray] = dict(fields["momenta"])
        self.constraint_residual: Optional[np.ndarray] = fields["constraint_residual"]
        self.constraint_velocity_residual: Optional[np.ndarray] = fields.get(
            "constraint_velocity_residual")
        self.multipliers: np.ndarray = fields["multipliers"]
        self.R: Optional[np.ndarray] = fields.get("R")
        self.Pi: Optional[np.ndarray] = fields.get("Pi")
        self.bodies: Dict[str, Body] = _bodies(fields, self.coordinates, self.q, self.p, self.v)
        self.observables: Dict[str, np.ndarray] = dict(fields.get("observables") or {})
        self.events: Dict[str, Dict[str, np.ndarray]] = {
            name: dict(records) for name, records in (fields.get("events") or {}).items()}
        at_times = fields.get("at_times")
        self.at_times: Optional[Dict[str, Any]] = None if at_times is None else dict(at_times)
        self.summary: Dict[str, Any] = (
            json.loads(fields["summary"]) if isinstance(fields["summary"], str)
            else fields["summary"])
        self.status: str = fields["status"]
        self.error: Optional[str] = fields["error"]
        self.warnings: List[str] = list(fields["warnings"])
        block = self.summary.get("sensitivity")
        arrays = fields.get("sensitivity")
        self.sensitivity: Optional[Sensitivity] = (
            Sensitivity(block, arrays) if block and arrays is not None else None)

    def __len__(self) -> int:
        return len(self.t)

    @property
    def ok(self) -> bool:
        """Whether every requested step was taken."""
        return self.status == "completed"

    @property
    def quaternion(self) -> Optional[np.ndarray]:
        """A rigid body's attitude as unit quaternions ``[w, x, y, z]`` (``k × 4``, ``w ≥ 0``),
        from ``R`` by Shepperd's method (the largest of ``4w², 4x², 4y², 4z²`` first, so no
        division by a small number); ``None`` for other systems."""
        if self.R is None:
            return None
        return np.array([_quaternion(r) for r in self.R]).reshape(len(self.R), 4)

    def final_state(self) -> Dict[str, Any]:
        """``t``, ``q`` and ``p`` of the last good state (as ``summary.json`` has them)."""
        final = self.summary["final_state"]
        return {"t": final["t"], "q": np.array(final["q"]), "p": np.array(final["p"])}

    def to_pandas(self) -> Any:
        """The samples as a ``pandas.DataFrame``: ``t``, ``q…``, ``p_…``, ``v_…``, ``energy``,
        ``J_…``, ``constraint_residual``, observables' columns and ``constraint_velocity_residual``,
        as ``trajectory.csv`` (plus ``v``); a
        quantity the run does not have (``energy`` of a discrete Lagrangian) has no column."""
        try:
            import pandas as pd
        except ImportError as e:  # pragma: no cover - depends on the environment
            raise ImportError("Solution.to_pandas() needs pandas: pip install pandas") from e
        columns: Dict[str, Any] = {"t": self.t}
        for i, name in enumerate(self.coordinates):
            columns[name] = self.q[:, i]
        for i, name in enumerate(self.coordinates):
            columns[f"p_{name}"] = self.p[:, i]
        if self.energy is not None:
            columns["energy"] = self.energy
        for name, values in self.momenta.items():
            columns[f"J_{name}"] = values
        if self.constraint_residual is not None:
            columns["constraint_residual"] = self.constraint_residual
        for i in range(self.multipliers.shape[1]):
            columns[f"lambda_{i}"] = self.multipliers[:, i]
        for name, values in self.observables.items():
            columns[name] = values
        if self.constraint_velocity_residual is not None:
            columns["constraint_velocity_residual"] = self.constraint_velocity_residual
        for i, name in enumerate(self.coordinates):
            columns[f"v_{name}"] = self.v[:, i]
        return pd.DataFrame(columns)

    def plot(self, ax: Any = None) -> Any:
        """The phase portrait (``q`` against ``p`` per coordinate) and the relative energy
        error against time (for a run without an energy, the momentum maps' drift, or an
        empty panel saying so), with matplotlib; returns the figure."""
        try:
            import matplotlib.pyplot as plt
        except ImportError as e:  # pragma: no cover - depends on the environment
            raise ImportError("Solution.plot() needs matplotlib: pip install matplotlib") from e
        if ax is None:
            fig, (phase, energy) = plt.subplots(1, 2, figsize=(10, 4))
        else:
            phase, energy = ax
            fig = phase.figure
        for i, name in enumerate(self.coordinates):
            phase.plot(self.q[:, i], self.p[:, i], lw=0.6, label=name)
        phase.set_xlabel("q")
        phase.set_ylabel("p")
        phase.set_title("phase portrait")
        phase.legend()
        if self.energy is not None:
            _relative_error(energy, self.t, self.energy, "(E - E0)/|E0|", "energy error")
        elif self.momenta:
            for name, values in self.momenta.items():
                energy.plot(self.t, values - values[0] if len(values) else values, lw=0.6,
                            label=f"J_{name}")
            energy.set_xlabel("t")
            energy.set_ylabel("J - J0")
            energy.set_title("momentum map drift (no energy: discrete Lagrangian)")
            energy.legend()
        else:
            energy.set_axis_off()
            energy.set_title("no energy: a discrete Lagrangian has no continuous L")
        fig.tight_layout()
        return fig

    def __repr__(self) -> str:
        s = self.summary
        energy = s.get("energy") or {}
        t_final = s.get("t_final")
        text = (f"Solution({s.get('name', '?')!r}, {self.status}, {len(self)} samples of "
                f"{len(self.coordinates)} coordinates {self.coordinates}, steps "
                f"{s.get('steps')}/{s.get('steps_requested')}, t_final={t_final!r}, "
                f"max |ΔE/E0|={energy.get('max_rel_error')!r}")
        for name, values in self.momenta.items():
            drift = s.get("momenta", {}).get(name, {}).get("max_abs_drift")
            text += f", max |ΔJ_{name}|={drift!r}"
        if self.error:
            text += f", error={self.error!r}"
        return text + ")"


def _relative_error(ax: Any, t: np.ndarray, values: np.ndarray, label: str, title: str) -> None:
    """``(x − x₀)/|x₀|`` against ``t`` on ``ax`` (unscaled if ``x₀ = 0``)."""
    x0 = values[0] if len(values) else 1.0
    scale = abs(x0) if x0 != 0 else 1.0
    ax.plot(t, (values - x0) / scale, lw=0.6)
    ax.set_xlabel("t")
    ax.set_ylabel(label)
    ax.set_title(title)


class Body:
    """One body of a multibody run: its samples as NumPy arrays (one row per stored sample).

    - ``x``, ``p``, ``v`` (``k × 3``): the centre of mass, its momentum ``m ẋ`` and velocity;
    - ``R`` (``k × 3 × 3``): the attitude, body → space;
    - ``Pi`` (``k × 3``): the body angular momentum ``Π = JΩ``;

    a particle (``[[system.particle]]``) has no attitude: its ``R`` and ``Pi`` are ``None``.
    """

    def __init__(self, name: str, x: np.ndarray, p: np.ndarray, v: np.ndarray,
                 R: Optional[np.ndarray], Pi: Optional[np.ndarray]) -> None:
        self.name = name
        self.x = x
        self.p = p
        self.v = v
        self.R = R
        self.Pi = Pi

    def __repr__(self) -> str:
        return f"Body({self.name!r}, {len(self.x)} samples)"


def _bodies(fields: Dict[str, Any], coordinates: List[str], q: np.ndarray, p: np.ndarray,
            v: np.ndarray) -> Dict[str, "Body"]:
    """The bodies then the particles of a multibody run, named by their centre coordinates
    ``<name>_x``; the first ``attitudes.shape[1]`` are the bodies."""
    attitudes = fields.get("attitudes")
    momenta = fields.get("body_momenta")
    if attitudes is None or momenta is None:
        return {}
    names = [c[:-2] for c in coordinates[::3]]
    out: Dict[str, Body] = {}
    for b, name in enumerate(names):
        columns = slice(3 * b, 3 * b + 3)
        velocity = v[:, columns] if v.shape[1] == q.shape[1] else np.empty((0, 3))
        turning = b < attitudes.shape[1]
        out[name] = Body(name, q[:, columns], p[:, columns], velocity,
                         attitudes[:, b] if turning else None,
                         momenta[:, columns] if turning else None)
    return out


def _quaternion(r: np.ndarray) -> np.ndarray:
    """The unit quaternion ``[w, x, y, z]`` (``w ≥ 0``) of the rotation ``r`` (Shepperd 1978)."""
    trace = r[0, 0] + r[1, 1] + r[2, 2]
    candidates = [1 + trace, 1 + 2 * r[0, 0] - trace, 1 + 2 * r[1, 1] - trace,
                  1 + 2 * r[2, 2] - trace]
    i = int(np.argmax(candidates))
    s = 2.0 * np.sqrt(candidates[i])
    if i == 0:
        q = [s / 4, (r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s, (r[1, 0] - r[0, 1]) / s]
    elif i == 1:
        q = [(r[2, 1] - r[1, 2]) / s, s / 4, (r[0, 1] + r[1, 0]) / s, (r[0, 2] + r[2, 0]) / s]
    elif i == 2:
        q = [(r[0, 2] - r[2, 0]) / s, (r[0, 1] + r[1, 0]) / s, s / 4, (r[1, 2] + r[2, 1]) / s]
    else:
        q = [(r[1, 0] - r[0, 1]) / s, (r[0, 2] + r[2, 0]) / s, (r[1, 2] + r[2, 1]) / s, s / 4]
    q = np.array(q)
    return -q if q[0] < 0 else q


def from_native(fields: Dict[str, Any]) -> Solution:
    """A solution from the native dictionary; raises :class:`SimulationError` if it failed."""
    solution = Solution(fields)
    if solution.status == "failed":
        raise SimulationError(f"the simulation failed: {solution.error}", solution)
    derivatives = solution.summary.get("sensitivity") or {}
    if derivatives.get("error"):
        raise SimulationError(
            f"the derivatives could not be computed: {derivatives['error']}", solution)
    return solution
