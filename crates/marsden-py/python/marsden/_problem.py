"""``marsden.Problem``: a mechanical system, its initial state and the integrator.

A problem is problem-file text (TOML). The keyword form writes that text from Python values
(SymPy expressions printed in the grammar), so ``Problem(...)``, ``Problem.from_toml`` and
``marsden run`` on the same file read the same thing and compute the same bits.
"""

from __future__ import annotations

import os
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

from . import _native, _sensitivity, _toml
from ._errors import ProblemError
from ._solution import Solution, from_native
from ._sympy import is_sympy, to_grammar

Expression = Any  # a string in the grammar, or a SymPy expression
Symmetries = Union[Mapping[str, Sequence[Expression]], Sequence[Tuple[str, Sequence[Expression]]]]

_ORIGIN = "<python>"


def _text(expr: Expression) -> str:
    """An expression as grammar text."""
    if isinstance(expr, str):
        return expr
    if is_sympy(expr):
        return to_grammar(expr)
    raise TypeError(f"expected an expression (str or SymPy), got {type(expr).__name__}")


def _name(coordinate: Any) -> str:
    """A coordinate's name: a string, a SymPy symbol or a dynamicsymbol ``theta(t)``."""
    if isinstance(coordinate, str):
        return coordinate
    if is_sympy(coordinate):
        return to_grammar(coordinate)
    raise TypeError(f"expected a coordinate name, got {coordinate!r}")


class Problem:
    """A mechanical system, its initial state and the integrator: what a problem file holds.

    Give a Lagrangian (or ``builtin=`` a catalog system, or a ``hamiltonian=``) as a string in
    the problem-file grammar or as a SymPy expression::

        >>> import marsden
        >>> pendulum = marsden.Problem(
        ...     lagrangian="0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)",
        ...     coordinates=["theta"], parameters={"m": 1.0, "l": 1.0, "g": 1.0},
        ...     q0=[1.5], v0=[0.0], method="midpoint", h=0.05, steps=1000)
        >>> solution = pendulum.solve()
        >>> solution.q.shape
        (1001, 1)

    Every value is checked at once; a mistake raises :class:`marsden.ProblemError` with the
    message of the ``marsden`` command (the offending line of :attr:`toml`, with a caret).

    Arguments: ``coordinates`` (names; velocities are ``<name>_dot``), ``parameters`` (name ->
    value), ``q0`` and one of ``v0`` / ``p0``, ``method`` (``midpoint``, ``trapezoid``,
    ``gauss-2``, ``lobatto-3``, ...), ``h`` and one of ``steps`` / ``t_end``; optional
    ``forces`` (one generalized force per coordinate), ``constraints`` (holonomic, ``φ(q) =
    0``), ``symmetries`` (name -> generator ``ξ_Q(q)``, monitored momentum maps),
    ``hamiltonian``, ``t0``, ``tolerance``, ``max_iterations``, ``project``, ``fast_paths``,
    ``compensated``, ``every`` (store every k-th step) and ``name``.
    """

    def __init__(
        self,
        lagrangian: Optional[Expression] = None,
        coordinates: Optional[Sequence[Any]] = None,
        parameters: Optional[Mapping[str, Any]] = None,
        q0: Optional[Sequence[float]] = None,
        v0: Optional[Sequence[float]] = None,
        p0: Optional[Sequence[float]] = None,
        method: Optional[str] = "midpoint",
        h: Optional[float] = None,
        steps: Optional[int] = None,
        t_end: Optional[float] = None,
        forces: Optional[Sequence[Expression]] = None,
        constraints: Optional[Sequence[Expression]] = None,
        symmetries: Optional[Symmetries] = None,
        hamiltonian: Optional[Expression] = None,
        *,
        builtin: Optional[str] = None,
        name: Optional[str] = None,
        t0: Optional[float] = None,
        tolerance: Optional[float] = None,
        max_iterations: Optional[int] = None,
        project: Optional[bool] = None,
        fast_paths: Optional[bool] = None,
        compensated: Optional[bool] = None,
        every: Optional[int] = None,
    ) -> None:
        system = [
            ("name", None if name is None else _toml.string(name)),
            ("builtin", None if builtin is None else _toml.string(builtin)),
            ("coordinates", None if coordinates is None
             else _toml.strings(_name(c) for c in coordinates)),
            ("parameters", None if parameters is None else _toml.parameters(parameters)),
            ("lagrangian", None if lagrangian is None else _toml.string(_text(lagrangian))),
            ("hamiltonian", None if hamiltonian is None else _toml.string(_text(hamiltonian))),
            ("forces", None if forces is None else _toml.strings(_text(f) for f in forces)),
            ("constraints", None if constraints is None
             else _toml.strings(_text(c) for c in constraints)),
        ]
        initial = [
            ("t0", None if t0 is None else _toml.number(float(t0))),
            ("q", None if q0 is None else _toml.floats(q0)),
            ("v", None if v0 is None else _toml.floats(v0)),
            ("p", None if p0 is None else _toml.floats(p0)),
            ("project", None if project is None else _bool(project)),
        ]
        integrator = [
            ("method", None if method is None else _toml.string(method)),
            ("h", None if h is None else _toml.number(float(h))),
            ("steps", None if steps is None else _toml.number(steps)),
            ("t_end", None if t_end is None else _toml.number(float(t_end))),
            ("tolerance", None if tolerance is None else _toml.number(float(tolerance))),
            ("max_iterations", None if max_iterations is None else _toml.number(max_iterations)),
            ("fast_paths", None if fast_paths is None else _bool(fast_paths)),
            ("compensated", None if compensated is None else _bool(compensated)),
        ]
        lines = _toml.table("system", system)
        for sym_name, generator in _symmetry_items(symmetries):
            lines += ["", "[[system.symmetry]]", f"name = {_toml.string(sym_name)}",
                      f"generator = {_toml.strings(_text(g) for g in generator)}"]
        lines += [""] + _toml.table("initial", initial)
        lines += [""] + _toml.table("integrator", integrator)
        if every is not None:
            lines += [""] + _toml.table("output", [("every", _toml.number(every))])
        self._init("\n".join(lines) + "\n", _ORIGIN)

    def _init(self, text: str, origin: str) -> None:
        self._text = text
        self._origin = origin
        self._info: Dict[str, Any] = dict(_native.check(text, origin))

    @classmethod
    def from_toml(cls, text: str, origin: str = "<toml>") -> "Problem":
        """A problem from problem-file text (``origin`` names it in error messages).

        >>> p = marsden.Problem.from_toml(open("examples/pendulum.toml").read())
        """
        problem = cls.__new__(cls)
        problem._init(text, origin)
        return problem

    @classmethod
    def load(cls, path: Union[str, "os.PathLike[str]"]) -> "Problem":
        """The problem file at ``path`` (``marsden run path`` computes the same)."""
        with open(path, encoding="utf-8") as f:
            text = f.read()
        return cls.from_toml(text, os.fspath(path))

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

    def solve(self, every: Optional[int] = None, progress: bool = False,
              sensitivity: Optional[_sensitivity.Request] = None) -> Solution:
        """Runs the problem (without the interpreter's lock; Ctrl-C raises
        ``KeyboardInterrupt`` within a few hundred steps) and returns the stored samples.

        ``every``: store every k-th step (and the first and the last); default: the
        problem's ``[output] every``, else 1. ``progress``: a progress line on stderr.
        ``sensitivity``: derivatives of the run, in :attr:`Solution.sensitivity` — ``True``
        for ``∂(q_k, p_k)/∂(q₀, p₀)``, a list of parameter names for ``∂(q_k, p_k)/∂θ``, or
        both as ``{"initial": True, "parameters": ["g"]}`` (the problem file's
        ``[sensitivity]`` table)::

            >>> s = pendulum.solve(sensitivity=["g", "l"])
            >>> s.sensitivity.column("g")      # ∂(θ, p_θ)/∂g at the last step

        Raises :class:`marsden.SimulationError` if the run fails part-way (its
        ``.solution`` holds the samples before the failure) or if the derivatives asked for
        could not be computed (its ``.solution`` holds the whole run).
        """
        text = self._text
        if sensitivity is not None:
            if self._info.get("sensitivity"):
                raise ProblemError("this problem already has a [sensitivity] table: leave out "
                                   "solve(sensitivity=...), or remove the table")
            text += _sensitivity.table(sensitivity)
        return from_native(_native.solve(text, self._origin, every, progress))

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


def _bool(value: bool) -> str:
    return "true" if value else "false"


def _symmetry_items(symmetries: Optional[Symmetries]) -> List[Tuple[str, Sequence[Any]]]:
    if symmetries is None:
        return []
    if isinstance(symmetries, Mapping):
        return list(symmetries.items())
    return [(n, g) for n, g in symmetries]
