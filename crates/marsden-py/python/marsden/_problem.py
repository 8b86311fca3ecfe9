"""``marsden.Problem``: a mechanical system, its initial state and the integrator.

A problem is problem-file text (TOML). The keyword form writes that text from Python values
(SymPy expressions printed in the grammar), so ``Problem(...)``, ``Problem.from_toml`` and
``marsden run`` on the same file read the same thing and compute the same bits.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any, Dict, List, Mapping, Optional, Sequence, Union

from . import _native, _sensitivity
from . import _keywords as kw
from . import _messages, _problem_text, _progress
from ._errors import ProblemError
from ._optimize import OptimalControlSolution
from ._solution import Solution, from_native

if TYPE_CHECKING:  # pragma: no cover
    from ._simulation import Simulation

Expression = Any  # a string in the grammar, a SymPy expression or a number
Symmetries = kw.Symmetries

_ORIGIN = "<python>"


class Problem:
    """A mechanical system, its initial state and the integrator: what a problem file holds.

    Give a Lagrangian (or ``builtin=`` a catalog system, a ``hamiltonian=``, or your own
    ``discrete_lagrangian=``) as a string in the problem-file grammar or as a SymPy
    expression::

        >>> import marsden
        >>> pendulum = marsden.Problem(
        ...     lagrangian="0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)",
        ...     coordinates=["theta"], parameters={"m": 1.0, "l": 1.0, "g": 1.0},
        ...     q0=[1.5], v0=[0.0], method="midpoint", h=0.05, steps=1000)
        >>> solution = pendulum.solve()
        >>> solution.q.shape
        (1001, 1)

    Every value is checked at once; a mistake raises :class:`marsden.ProblemError` naming the
    keyword at fault (with a caret under the fault inside an expression).

    Every key of a problem file has its keyword:

    - the system: ``coordinates`` (names, or one name; velocities are ``<name>_dot``),
      ``parameters`` (name -> value), and one of ``lagrangian``, ``builtin``,
      ``hamiltonian`` (``H(q, p_q)``) and ``discrete_lagrangian`` (``L_d`` written with
      ``<q>_0``, ``<q>_1``, ``h`` and ``t``: the method itself, so no ``method``, ``v0``,
      ``forces`` or ``constraints`` with it, and no energy in the solution); optional
      ``forces`` (one generalized force per coordinate), ``constraints`` (holonomic,
      ``φ(q) = 0``), ``symmetries`` (name -> generator ``ξ_Q(q)``, or name ->
      ``{"rotation": "z"}``: monitored momentum maps), ``rotation`` / ``translation`` (an
      axis or a list of axes: the named symmetries ``Lz``, ``Px``, ... of Cartesian
      coordinates) and ``name``. An expression is a string, a SymPy expression or a number.
    - a rigid body instead (a configuration on SO(3), stepped by the Lie group variational
      integrator): ``rigid_body`` (``{"inertia": [J1, J2, J3] or a 3×3 matrix, "mass": m}``),
      ``potential`` (``U`` in ``R11`` … ``R33``, and ``x``, ``y``, ``z`` with a mass),
      ``torques`` (body frame), ``rotation`` (in space) / ``body_rotation`` (about body axes);
      initially ``R0`` / ``quaternion0`` / ``rotation_vector0`` and ``Omega0`` / ``Pi0``
      (``solution.R``, ``solution.Pi``, ``solution.quaternion``).
    - jointed bodies instead: ``gravity`` (``[gx, gy, gz]``), ``bodies`` (a list of
      ``{"name", "mass", "inertia"}``), ``particles`` (point masses: ``{"name", "mass"}``;
      spherical and distance joints at their position), ``joints`` (``{"kind": "revolute", "bodies": ["ground",
      "a"], "at": [...], "axis": [...]}``, ``spherical``, ``prismatic``, ``fixed``, ``distance``
      with ``length``), ``springs`` (``{"bodies", "at", "stiffness", "rest_length"}``),
      ``dampers`` (``{"bodies", "at", "coefficient"}``), and initially ``bodies0`` (``{"a":
      {"x": ..., "R": ..., "v": ..., "Omega": ...}}``, or ``p``, ``Pi``, ``quaternion``,
      ``rotation_vector``): the file's ``[[system.body]]``, ``[[system.joint]]``, … tables
      with the same keys (``solution.bodies["a"].R``).
    - the initial state: ``q0`` and one of ``v0`` / ``p0`` (or ``bodies_file``, an N-body
      file of ``builtin="nbody"``, relative to the working directory), ``t0``, ``project``
      (project onto the constraints first).
    - the integrator: ``method`` (default ``midpoint``; ``trapezoid``, ``gauss-2``,
      ``lobatto-3``, ...), ``h`` and one of ``steps`` / ``t_end`` (a ``t_end`` off the
      grid of ``h`` ends with one shorter step), ``tolerance``, ``max_iterations``,
      ``fast_paths``, ``compensated``.
    - the output: ``every`` (store every k-th step), ``angles`` (coordinates that are
      angles: plots wrap them), ``times`` (the state at these times, between grid points
      too, read off the step's interpolant: ``solution.at_times``; with ``exact_times=True``
      each reached by a step of its own size instead), and for a file run by
      ``marsden run``: ``output_dir``, ``output_format`` (``csv``, ``npy``) and ``plots``.
    - the analysis: ``every_step`` (monitor energy and momenta at every step, not only the
      stored ones) and ``certify`` (the symplecticity and equivariance defects, in
      ``solution.summary["certificates"]``).
    - ``sensitivity`` (as in :meth:`solve`) and ``sweep`` (``{"parameter": "l", "values":
      [...]}`` or ``{"initial": "q[0]", "range": {"start": ..., "stop": ..., "count":
      ...}}``: run it with :meth:`sweep`).
    """

    def __init__(
        self,
        lagrangian: Optional[Expression] = None,
        coordinates: Optional[Union[str, Sequence[Any]]] = None,
        parameters: Optional[Mapping[str, Any]] = None,
        q0: Optional[Sequence[float]] = None,
        v0: Optional[Sequence[float]] = None,
        p0: Optional[Sequence[float]] = None,
        method: Optional[str] = None,
        h: Optional[float] = None,
        steps: Optional[int] = None,
        t_end: Optional[float] = None,
        forces: Optional[Sequence[Expression]] = None,
        constraints: Optional[Sequence[Expression]] = None,
        symmetries: Optional[Symmetries] = None,
        hamiltonian: Optional[Expression] = None,
        *,
        builtin: Optional[str] = None,
        discrete_lagrangian: Optional[Expression] = None,
        name: Optional[str] = None,
        rotation: Optional[Union[str, Sequence[str]]] = None,
        translation: Optional[Union[str, Sequence[str]]] = None,
        t0: Optional[float] = None,
        bodies_file: Optional[Union[str, "os.PathLike[str]"]] = None,
        project: Optional[bool] = None,
        tolerance: Optional[float] = None,
        max_iterations: Optional[int] = None,
        fast_paths: Optional[bool] = None,
        compensated: Optional[bool] = None,
        every: Optional[int] = None,
        angles: Optional[Union[str, Sequence[Any]]] = None,
        output_dir: Optional[Union[str, "os.PathLike[str]"]] = None,
        output_format: Optional[str] = None,
        plots: Optional[bool] = None,
        times: Optional[Sequence[float]] = None,
        exact_times: Optional[bool] = None,
        every_step: Optional[bool] = None,
        certify: Optional[bool] = None,
        sensitivity: Optional[_sensitivity.Request] = None,
        sweep: Optional[Mapping[str, Any]] = None,
        rigid_body: Optional[Any] = None,
        potential: Optional[Expression] = None,
        torques: Optional[Sequence[Expression]] = None,
        body_rotation: Optional[Union[str, Sequence[str]]] = None,
        R0: Optional[Any] = None,
        quaternion0: Optional[Sequence[float]] = None,
        rotation_vector0: Optional[Sequence[float]] = None,
        Omega0: Optional[Sequence[float]] = None,
        Pi0: Optional[Sequence[float]] = None,
        gravity: Optional[Sequence[float]] = None,
        bodies: Optional[Sequence[Mapping[str, Any]]] = None,
        particles: Optional[Sequence[Mapping[str, Any]]] = None,
        joints: Optional[Sequence[Mapping[str, Any]]] = None,
        springs: Optional[Sequence[Mapping[str, Any]]] = None,
        dampers: Optional[Sequence[Mapping[str, Any]]] = None,
        bodies0: Optional[Mapping[str, Mapping[str, Any]]] = None,
    ) -> None:
        generated = _problem_text.write(_problem_text.Keywords(
            lagrangian=lagrangian, coordinates=coordinates, parameters=parameters, q0=q0,
            v0=v0, p0=p0, method=method, h=h, steps=steps, t_end=t_end, forces=forces,
            constraints=constraints, symmetries=symmetries, hamiltonian=hamiltonian,
            builtin=builtin, discrete_lagrangian=discrete_lagrangian, name=name,
            rotation=rotation, translation=translation, t0=t0, bodies_file=bodies_file,
            project=project, tolerance=tolerance, max_iterations=max_iterations,
            fast_paths=fast_paths, compensated=compensated, every=every, angles=angles,
            output_dir=output_dir, output_format=output_format, plots=plots, times=times,
            exact_times=exact_times,
            every_step=every_step, certify=certify, sensitivity=sensitivity, sweep=sweep,
            rigid_body=rigid_body, potential=potential, torques=torques,
            body_rotation=body_rotation, R0=R0, quaternion0=quaternion0,
            rotation_vector0=rotation_vector0, Omega0=Omega0, Pi0=Pi0, gravity=gravity,
            bodies=bodies, particles=particles, joints=joints, springs=springs, dampers=dampers, bodies0=bodies0))
        try:
            self._init(generated.text, _ORIGIN)
        except ProblemError as e:
            raise ProblemError(_messages.for_keywords(str(e), generated)) from None
        self._generated: Optional[kw.Generated] = generated

    def _init(self, text: str, origin: str) -> None:
        self._text = text
        self._origin = origin
        self._generated = None
        # Checked once: solve(), sweep() and simulation() run the checked problem, without
        # reading the text or preparing the initial state again.
        self._checked = _native.check(text, origin)
        self._info: Dict[str, Any] = dict(self._checked.info)

    def _error(self, error: ProblemError) -> ProblemError:
        """``error`` in the terms the problem was given in (keywords, or text)."""
        if self._generated is not None:
            return ProblemError(_messages.for_keywords(str(error), self._generated))
        return error

    @classmethod
    def from_toml(cls, text: str, origin: str = "<toml>") -> "Problem":
        """A problem from problem-file text (``origin`` names it in error messages).

        >>> p = marsden.Problem.from_toml(open("examples/pendulum.toml").read())
        """
        problem = cls.__new__(cls)
        try:
            problem._init(text, origin)
        except ProblemError as e:
            raise ProblemError(_messages.for_text(str(e), origin)) from None
        return problem

    @classmethod
    def load(cls, path: Union[str, "os.PathLike[str]"]) -> "Problem":
        """The problem file at ``path`` (``marsden run path`` computes the same); paths in
        it (an N-body ``file``) are relative to the file's directory."""
        with open(path, encoding="utf-8") as f:
            text = f.read()
        problem = cls.__new__(cls)
        problem._init(text, os.fspath(path))
        return problem

    @classmethod
    def builtin(cls, name: str, **kwargs: Any) -> "Problem":
        """A catalog system (see :func:`marsden.systems`), with ``parameters`` overriding its
        defaults and the other arguments of :class:`Problem`.

        >>> kepler = marsden.Problem.builtin("kepler", q0=[0.4, 0.0], p0=[0.0, 2.0],
        ...                                  h=0.01, steps=1000)
        """
        return cls(builtin=name, **kwargs)

    @property
    def toml(self) -> str:
        """The problem-file text of this problem (save it and ``marsden run`` it)."""
        return self._text

    @property
    def name(self) -> str:
        """The run's name."""
        return self._info["name"]

    @property
    def coordinates(self) -> List[str]:
        """Coordinate names, in the order of the columns of ``q``, ``p`` and ``v``."""
        return list(self._info["coordinates"])

    @property
    def parameters(self) -> Dict[str, float]:
        """Every scalar parameter with its value (a builtin's defaults filled in)."""
        return dict(self._info["parameters"])

    @property
    def method(self) -> str:
        """The integrator."""
        return self._info["method"]

    @property
    def h(self) -> float:
        """The time step."""
        return self._info["h"]

    @property
    def steps(self) -> int:
        """The number of steps."""
        return self._info["steps"]

    def solve(self, every: Optional[int] = None, progress: _progress.Request = False,
              sensitivity: Optional[_sensitivity.Request] = None,
              dir: Optional[str] = None, checkpoint_every: Optional[int] = None) -> Solution:
        """Runs the problem (without the interpreter's lock; Ctrl-C raises
        ``KeyboardInterrupt`` within a few hundred steps) and returns the stored samples.

        ``every``: store every k-th step (and the first and the last); default: the
        problem's ``[output] every``, else 1. ``progress``: ``True`` for a report on
        ``sys.stderr`` (a line redrawn in place on a terminal, else one line per tenth of the
        run), or a function called as ``f(step, total, elapsed_seconds, done)`` every few
        hundred steps. ``sensitivity``: derivatives of the run, in
        :attr:`Solution.sensitivity` — ``True`` for ``∂(q_k, p_k)/∂(q₀, p₀)``, a list of
        parameter names for ``∂(q_k, p_k)/∂θ``, or both as ``{"initial": True,
        "parameters": ["g"]}`` (the problem file's ``[sensitivity]`` table)::

            >>> s = pendulum.solve(sensitivity=["g", "l"])
            >>> s.sensitivity.column("g")      # ∂(θ, p_θ)/∂g at the last step

        ``dir``: also write the files of ``marsden run`` there (``trajectory.csv``,
        ``summary.json``, plots). ``checkpoint_every`` (with ``dir``): save a checkpoint every
        this many steps, so that a run killed part-way continues with
        :func:`marsden.resume` and leaves the files of the uninterrupted run::

            >>> pendulum.solve(dir="out/long", checkpoint_every=100_000)
            >>> marsden.resume("out/long")          # after a kill, in a new process

        Raises :class:`marsden.ProblemError` for a problem with a sweep (run it with
        :meth:`sweep`), and :class:`marsden.SimulationError` if the run fails part-way (its
        ``.solution`` holds the samples before the failure) or if the derivatives asked for
        could not be computed (its ``.solution`` holds the whole run).
        """
        if self.is_optimal_control:
            raise ProblemError(
                "error: this problem has an [optimal_control] table: solve it with "
                "problem.optimize()")
        if self._info.get("sweep") is not None:
            label, members = self._info["sweep"]
            raise ProblemError(
                f"error: this problem is a sweep over {label} ({len(members)} members); "
                "solve() runs one problem\n"
                "  = help: run every member with problem.sweep() (or marsden.sweep(problem)), "
                "or `marsden run` the file")
        if sensitivity is not None and self._info.get("sensitivity"):
            raise ProblemError("this problem already has a [sensitivity] table: leave out "
                               "solve(sensitivity=...), or remove the table")
        # With derivatives asked, another problem: the text with the [sensitivity] table,
        # checked by the run.
        text = None if sensitivity is None else self._text + _sensitivity.table(sensitivity)
        try:
            callback = _progress.callback(progress)
            out = None if dir is None else str(dir)
            if text is None:
                fields = self._checked.solve(every, callback, out, checkpoint_every)
            else:
                fields = _native.solve(text, self._origin, every, callback, out,
                                       checkpoint_every)
        except ProblemError as e:
            raise self._error(e) from None
        return from_native(fields)

    def simulation(self) -> "Simulation":
        """The problem as a :class:`marsden.Simulation`, stepped as you go from its initial
        state (``sim.step()``, ``sim.integrate(t)``, ``sim.state``)::

            >>> sim = pendulum.simulation()
            >>> sim.integrate(10.0); sim.state["q"]
        """
        from ._simulation import Simulation

        return Simulation(self)

    @property
    def is_optimal_control(self) -> bool:
        """Whether the problem has an ``[optimal_control]`` table (solve it with
        :meth:`optimize`)."""
        return bool(self._info.get("optimal_control"))

    def optimize(self) -> OptimalControlSolution:
        """Solves the problem's ``[optimal_control]`` (discrete mechanics and optimal control,
        as ``marsden optimize`` does, without writing files; the interpreter's lock released).

        A solve that does not converge returns its last iterate, with ``status`` saying why::

            >>> s = marsden.Problem.from_toml(text).optimize()
            >>> s.status, s.cost, s.q[-1], s.u[:, 0]

        Raises :class:`marsden.ProblemError` for a problem without ``[optimal_control]``.
        """
        if not self.is_optimal_control:
            raise ProblemError(
                "error: this problem has no [optimal_control] table: optimize() solves optimal "
                "control problems\n  = help: run it with problem.solve()")
        try:
            fields = _native.optimize(self._text, self._origin)
        except ProblemError as e:
            raise self._error(e) from None
        return OptimalControlSolution(fields)

    def sweep(self, parameter: Optional[str] = None, values: Optional[Sequence[float]] = None,
              executor: Any = None, **options: Any) -> List[Any]:
        """:func:`marsden.sweep` of this problem: its own sweep (a ``[sweep]`` table or
        ``sweep=``) when called without ``parameter`` and ``values``.

        >>> marsden.Problem.load("examples/pendulum_sweep.toml").sweep()
        """
        from ._sweep import sweep

        return sweep(self, parameter, values, executor, **options)

    def __repr__(self) -> str:
        i = self._info
        return (f"Problem({i['name']!r}, coordinates={i['coordinates']}, {i['lagrangian']}, "
                f"method={i['method']!r}, h={i['h']!r}, steps={i['steps']})")

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Problem) and self._text == other._text

    def __hash__(self) -> int:
        return hash(self._text)

    def __getstate__(self) -> Dict[str, Any]:
        return {"text": self._text, "origin": self._origin}

    def __setstate__(self, state: Dict[str, Any]) -> None:
        self._init(state["text"], state["origin"])
