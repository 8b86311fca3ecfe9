"""A problem stepped as you go: :class:`Simulation` (``problem.simulation()``)."""

from __future__ import annotations

import json
import os
from typing import TYPE_CHECKING, Any, Dict, Optional, Union

import numpy as np

from . import _native, _progress
from ._errors import ProblemError, SimulationError
from ._solution import Solution, from_native

if TYPE_CHECKING:  # pragma: no cover
    from ._problem import Problem

#: The format of :meth:`Simulation.save`'s file.
_FORMAT = "marsden-simulation 1"


class Simulation:
    """A problem's run taken in stretches, as REBOUND's ``sim.integrate(t)`` and
    ``solve_ivp``'s users expect: ``step()`` takes steps of the problem's ``h``, ``integrate(t)``
    runs until the time ``t`` exactly (a shorter, still variational last step when ``t`` is off
    the grid), and ``state`` is where the run stands::

        >>> sim = pendulum.simulation()
        >>> sim.integrate(10.0)          # the Solution of the stretch from t0 to 10
        >>> sim.step(); sim.state["q"]   # one more step of h
        >>> sim.save("pendulum.sim")     # ... and in another process:
        >>> sim = marsden.Simulation.load("pendulum.sim"); sim.integrate(20.0)

    The method's step is a map of ``(q_k, p_k)`` (the position–momentum form of the discrete
    Euler–Lagrange equations), so each stretch continues from the state ``(t, q, p)`` the one
    before it reached: the same discrete flow as one run of the whole time, to the Newton
    tolerance of the steps (bit for bit for explicit steps). A simulation saved and loaded
    continues exactly as the one that was not stopped. Each stretch starts a run from its state
    (about a millisecond): take many steps per call where you can.
    Rigid bodies, multibody systems, sweeps, ``[sensitivity]`` and control tables are
    refused; ``[output] times`` are left to :meth:`Problem.solve` (ask ``integrate`` for the
    times instead). A stretch stopped by an event leaves the simulation at that step (its
    ``status`` says ``"stopped by event …"``); a failing stretch raises
    :class:`marsden.SimulationError` and leaves the simulation at the last good state.
    """

    def __init__(self, problem: "Problem") -> None:
        if problem.is_optimal_control:
            raise ProblemError("error: an [optimal_control] problem is solved with optimize(), "
                               "not stepped")
        self._text: str = problem._text
        self._origin: str = problem._origin
        # The problem as checked: its initial state prepared then, its stretches run without
        # reading the text again.
        self._problem = problem
        try:
            t, q, p = problem._checked.initial_state()
        except ProblemError as e:
            raise problem._error(e) from None
        self.t: float = t
        self.q: np.ndarray = np.array(q, dtype=float)
        self.p: np.ndarray = np.array(p, dtype=float)
        #: Steps taken since the start.
        self.steps: int = 0

    @property
    def state(self) -> Dict[str, Any]:
        """``{"t": t, "q": q, "p": p}``: where the run stands (copies)."""
        return {"t": self.t, "q": self.q.copy(), "p": self.p.copy()}

    def step(self, n: int = 1) -> Solution:
        """Takes ``n`` steps of the problem's ``h``; returns their :class:`Solution` (the
        states from the current one on)."""
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
            raise ProblemError(f"error: step(n): n must be a whole number of steps >= 1, got {n!r}")
        return self._stretch(steps=int(n))

    def integrate(self, t: float, every: Optional[int] = None,
                  progress: _progress.Request = False) -> Solution:
        """Runs until the time ``t`` exactly; returns the stretch's :class:`Solution` (every
        ``every``-th step stored, and its first and last states). ``progress`` as in
        :meth:`Problem.solve`."""
        if not np.isfinite(t) or t <= self.t:
            raise ProblemError(f"error: integrate(t): t = {t!r} is not after the current time "
                               f"{self.t!r}")
        return self._stretch(t_end=float(t), every=every, progress=progress)

    def _stretch(self, steps: Optional[int] = None, t_end: Optional[float] = None,
                 every: Optional[int] = None, progress: _progress.Request = False) -> Solution:
        state = (self.t, [float(x) for x in self.q], [float(x) for x in self.p])
        fields = self._problem._checked.stretch(state, steps=steps, t_end=t_end, every=every,
                                                progress=_progress.callback(progress))
        try:
            solution = from_native(fields)
        except SimulationError as e:
            self._advance(e.solution)
            raise
        self._advance(solution)
        return solution

    def _advance(self, solution: Solution) -> None:
        """The state after ``solution``: its last (good) stored state."""
        if len(solution.t) == 0:
            return
        self.t = float(solution.t[-1])
        self.q = np.array(solution.q[-1], dtype=float)
        self.p = np.array(solution.p[-1], dtype=float)
        self.steps += int(solution.summary.get("steps", 0))

    def save(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Writes the problem and the state to ``path`` (JSON; the numbers exactly: Python's
        ``repr`` of a float reads back to the same bits), for :meth:`load`."""
        record = {"format": _FORMAT, "text": self._text, "origin": self._origin,
                  "t": self.t, "q": [float(x) for x in self.q],
                  "p": [float(x) for x in self.p], "steps": self.steps}
        tmp = f"{os.fspath(path)}.tmp"
        with open(tmp, "w", encoding="utf-8") as f:
            json.dump(record, f)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)

    @classmethod
    def from_checkpoint(cls, directory: Union[str, "os.PathLike[str]"]) -> "Simulation":
        """The run whose checkpoint is in ``directory`` (``marsden run --checkpoint-every``,
        ``problem.solve(dir=..., checkpoint_every=...)``, or a run stopped by a signal), as a
        simulation standing at the checkpoint's state, to step on from interactively. The
        integrator's carried data (Newton's predictor history) is not taken over: the steps
        agree with ``marsden.resume`` to the Newton tolerance (bit for bit for explicit steps).

            >>> sim = marsden.Simulation.from_checkpoint("out/long")
            >>> sim.t, sim.steps
            >>> sim.integrate(sim.t + 10.0)
        """
        from ._problem import Problem

        text, origin, t, q, p, steps = _native.checkpoint_state(os.fspath(directory))
        sim = cls(Problem.from_toml(text, origin=origin))
        sim.t = float(t)
        sim.q = np.array(q, dtype=float)
        sim.p = np.array(p, dtype=float)
        sim.steps = int(steps)
        return sim

    @classmethod
    def load(cls, path: Union[str, "os.PathLike[str]"]) -> "Simulation":
        """The simulation :meth:`save` wrote to ``path``, continuing where it stood."""
        from ._problem import Problem

        with open(path, encoding="utf-8") as f:
            try:
                record = json.load(f)
            except json.JSONDecodeError as e:
                raise ProblemError(f"error: {os.fspath(path)} is not a saved simulation: {e}") \
                    from None
        if not isinstance(record, dict) or record.get("format") != _FORMAT:
            raise ProblemError(f"error: {os.fspath(path)} is not a saved simulation "
                               f"(expected the format {_FORMAT!r})")
        sim = cls(Problem.from_toml(record["text"], origin=record["origin"]))
        sim.t = float(record["t"])
        sim.q = np.array(record["q"], dtype=float)
        sim.p = np.array(record["p"], dtype=float)
        sim.steps = int(record["steps"])
        return sim

    def __repr__(self) -> str:
        return f"Simulation(t={self.t!r}, steps={self.steps}, q={self.q.tolist()})"
