"""Problem text from the keyword arguments of :class:`marsden.Problem`, with a map from each
generated line back to the keyword that wrote it.

The keyword form writes a problem file and the problem-file library reads it as it reads one
on disk. Its messages then speak of that text (``[integrator] needs ...``, a line and a column
of it); the map lets :mod:`marsden._messages` say instead which keyword is at fault and, for
an expression, where in the expression the user wrote.

Every value that reads as an expression (a Lagrangian, a force, a generator component) may be
a string in the grammar, a SymPy expression or a plain number (``forces=[1, 0]``).
"""

from __future__ import annotations

import numbers
from dataclasses import dataclass, field
from typing import Any, Dict, Iterable, List, Mapping, Optional, Sequence, Tuple, Union

from . import _sensitivity, _toml
from ._errors import ProblemError
from ._sympy import is_sympy, to_grammar

Expression = Any  # a string in the grammar, a SymPy expression or a number
#: A symmetry: its generator (one expression per coordinate) or a named one,
#: ``{"rotation": "z"}`` / ``{"translation": "x"}``.
Generator = Union[Sequence[Expression], Mapping[str, str]]
Symmetries = Union[Mapping[str, Generator], Sequence[Tuple[str, Generator]]]


def expression(expr: Expression, keyword: str = "expression") -> str:
    """An expression as grammar text: a string as written, a SymPy expression printed, a
    number (``int``, ``float``, a NumPy or SymPy number) as its shortest exact text."""
    if isinstance(expr, str):
        return expr
    if is_sympy(expr):
        return to_grammar(expr)
    if isinstance(expr, numbers.Real) and not isinstance(expr, bool):
        text = _toml.number(expr)
        if text in ("nan", "inf", "-inf"):
            raise ProblemError(f"error: {keyword}: {text} is not an expression")
        return f"({text})" if text.startswith("-") else text
    raise ProblemError(f"error: {keyword}: expected an expression (a string in the grammar, a "
                       f"SymPy expression or a number), got {type(expr).__name__} {expr!r}")


def names(value: Any, keyword: str) -> List[str]:
    """Names (coordinates, angles): a list of strings or SymPy symbols; a single string is
    one name (``coordinates="theta"``)."""
    if isinstance(value, str) or is_sympy(value):
        value = [value]
    out = []
    for item in value:
        if isinstance(item, str):
            out.append(item)
        elif is_sympy(item):
            out.append(to_grammar(item))
        else:
            raise ProblemError(f"error: {keyword}: expected names (strings or SymPy symbols), "
                               f"got {item!r}")
    return out


@dataclass(frozen=True)
class Piece:
    """A string of a generated value: what the user wrote and where its literal starts."""

    #: The keyword as the user would write it (``lagrangian``, ``forces[1]``).
    label: str
    #: The string as written (without TOML quoting).
    source: str
    #: 0-based character column of the opening quote in the generated line.
    column: int


@dataclass(frozen=True)
class Line:
    """A generated ``key = value`` line and the keyword it came from."""

    #: The keyword as the user would write it (``q0``, ``symmetries['Lz']``).
    keyword: str
    #: The strings in the value, for pointing inside them.
    pieces: Tuple[Piece, ...] = ()

    def piece_at(self, column: int) -> Optional[Piece]:
        """The string whose literal covers the 0-based ``column``, if any."""
        for piece in self.pieces:
            if piece.column <= column < piece.column + len(_toml.string(piece.source)):
                return piece
        return None


@dataclass
class Generated:
    """Problem text and, by 1-based line number, the keyword behind each generated line."""

    lines: List[str] = field(default_factory=list)
    origins: Dict[int, Line] = field(default_factory=dict)

    @property
    def text(self) -> str:
        """The problem file."""
        return "\n".join(self.lines) + "\n"

    def table(self, header: str, entries: Iterable[Tuple[str, str, Any]]) -> None:
        """``[header]`` and one line per entry ``(toml key, keyword, value)`` whose value is
        not ``None``; a value is a TOML text, or a :class:`Value` with strings to point into."""
        if self.lines:
            self.lines.append("")
        self.lines.append(header)
        for key, keyword, value in entries:
            if value is None:
                continue
            if not isinstance(value, Value):
                value = Value(str(value))
            prefix = f"{_toml.key(key)} = "
            pieces = tuple(Piece(label, source, len(prefix) + offset)
                           for label, source, offset in value.strings)
            self.lines.append(prefix + value.text)
            self.origins[len(self.lines)] = Line(keyword, pieces)

    def raw(self, text: str) -> None:
        """Lines written elsewhere (no keyword map: messages about them keep no location)."""
        self.lines += [""] + text.strip("\n").split("\n")


@dataclass(frozen=True)
class Value:
    """A TOML value and the strings in it: ``(label, source, offset in text)``."""

    text: str
    strings: Tuple[Tuple[str, str, int], ...] = ()

    @classmethod
    def string(cls, label: str, source: str) -> "Value":
        """A TOML string."""
        return cls(_toml.string(source), ((label, source, 0),))

    @classmethod
    def strings_of(cls, label: str, sources: Sequence[str]) -> "Value":
        """A TOML array of strings, each labelled ``label[i]``."""
        text, strings = "[", []
        for i, source in enumerate(sources):
            if i:
                text += ", "
            strings.append((f"{label}[{i}]", source, len(text)))
            text += _toml.string(source)
        return cls(text + "]", tuple(strings))


def maybe(convert: Any, value: Any) -> Any:
    """``convert(value)``, or ``None`` for ``None``."""
    return None if value is None else convert(value)


def boolean(value: Any) -> str:
    """A TOML boolean."""
    return "true" if value else "false"


def symmetry_items(symmetries: Optional[Symmetries]) -> List[Tuple[str, Generator]]:
    """``(name, generator)`` pairs of a mapping or a sequence of pairs."""
    if symmetries is None:
        return []
    if isinstance(symmetries, Mapping):
        return list(symmetries.items())
    return [(n, g) for n, g in symmetries]


def symmetry(out: Generated, name: Optional[str], generator: Generator) -> None:
    """One ``[[system.symmetry]]``: a generator list, or a named rotation or translation."""
    keyword = "symmetries" if name is None else f"symmetries[{name!r}]"
    entries: List[Tuple[str, str, Any]] = [("name", keyword, maybe(_toml.string, name))]
    if isinstance(generator, Mapping):
        unknown = set(generator) - {"rotation", "translation"}
        if unknown:
            raise ProblemError(f"error: {keyword}: unknown key(s) {sorted(unknown)}; a named "
                               "symmetry is {'rotation': axis} or {'translation': axis}")
        for key in ("rotation", "translation"):
            if key in generator:
                entries.append((key, keyword, Value.string(keyword, str(generator[key]))))
    else:
        if isinstance(generator, (str, numbers.Number)) or is_sympy(generator):
            generator = [generator]
        texts = [expression(g, f"{keyword}[{i}]") for i, g in enumerate(generator)]
        entries.append(("generator", keyword, Value.strings_of(keyword, texts)))
    out.table("[[system.symmetry]]", entries)


def named_symmetries(out: Generated, key: str, axes: Union[None, str, Sequence[str]]) -> None:
    """``rotation="z"`` or ``translation=["x", "y"]``: one named symmetry per axis."""
    if axes is None:
        return
    for axis in [axes] if isinstance(axes, str) else list(axes):
        out.table("[[system.symmetry]]", [(key, key, Value.string(key, str(axis)))])


def sweep(out: Generated, request: Mapping[str, Any], header: str = "[sweep]") -> None:
    """``sweep={"parameter": "l", "values": [...]}`` (or ``"initial": "q[0]"``, ``"range":
    {"start": .., "stop": .., "count": ..}``, and a further axis under ``"and"``)."""
    unknown = set(request) - {"parameter", "initial", "values", "range", "and"}
    if unknown:
        raise ProblemError(f"error: sweep: unknown key(s) {sorted(unknown)}; the keys are "
                           "'parameter' or 'initial', 'values' or 'range', and 'and'")
    span = request.get("range")
    entries = [
        ("parameter", "sweep", maybe(lambda p: Value.string("sweep", p), request.get("parameter"))),
        ("initial", "sweep", maybe(lambda p: Value.string("sweep", p), request.get("initial"))),
        ("values", "sweep", maybe(_toml.floats, request.get("values"))),
        ("range", "sweep", maybe(_range, span)),
    ]
    out.table(header, entries)
    if request.get("and") is not None:
        sweep(out, request["and"], header[:-1] + ".and]")


def _range(span: Mapping[str, Any]) -> str:
    items = [f"{k} = {_toml.number(float(span[k]))}" for k in ("start", "stop") if k in span]
    if "count" in span:
        items.append(f"count = {_toml.number(span['count'])}")
    return "{ " + ", ".join(items) + " }"


def sensitivity(out: Generated, request: Any) -> None:
    """The ``[sensitivity]`` table (the forms of ``solve(sensitivity=...)``)."""
    out.raw(_sensitivity.table(request))


def parameters(values: Mapping[str, Any]) -> str:
    """The inline table of parameters."""
    return _toml.parameters(values)


def floats(values: Any, keyword: str) -> str:
    """A list of numbers (a single number is refused: the vector needs one per coordinate)."""
    if isinstance(values, (str, bytes)) or not hasattr(values, "__iter__"):
        raise ProblemError(f"error: {keyword}: expected a list of numbers, one per "
                           f"coordinate, got {values!r}")
    return _toml.floats(values)


def rigid_body(value: Any) -> str:
    """``rigid_body = { inertia = …, mass = … }`` from ``{"inertia": [J1, J2, J3] or 3×3,
    "mass": m}`` (or the inertia alone)."""
    spec = value if isinstance(value, Mapping) else {"inertia": value}
    unknown = set(spec) - {"inertia", "mass"}
    if unknown:
        raise ProblemError(f"error: rigid_body: unknown key {sorted(unknown)[0]!r}; "
                           "the keys are 'inertia' and 'mass'")
    items = []
    if "inertia" in spec:
        items.append(f"inertia = {matrix_or_vector(spec['inertia'], 'rigid_body inertia')}")
    if spec.get("mass") is not None:
        items.append(f"mass = {_toml.number(float(spec['mass']))}")
    return "{ " + ", ".join(items) + " }"


def matrix_or_vector(values: Any, keyword: str) -> str:
    """A list of numbers, or a list of rows of numbers (a NumPy array of either)."""
    rows = list(values) if hasattr(values, "__iter__") else None
    if rows is None or isinstance(values, (str, bytes)):
        raise ProblemError(f"error: {keyword}: expected numbers or rows of numbers, "
                           f"got {values!r}")
    if rows and hasattr(rows[0], "__iter__"):
        return "[" + ", ".join(_toml.floats(row) for row in rows) + "]"
    return _toml.floats(rows)
