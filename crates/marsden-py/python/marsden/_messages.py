"""The problem-file library's messages, re-phrased for whoever did not write a problem file.

A problem built from keywords is checked as the text it generates, so its messages first speak
TOML (``[integrator] needs the time step `h```) and point at a line of a file the user never
saw. :func:`for_keywords` turns such a message into keyword terms (``give the time step
h=``) and replaces the pointer by the keyword at fault, keeping the caret only inside an
expression the user wrote. Messages of ``from_toml`` and ``load`` are left as they are (the
caret points into the user's own text), except for the one that names the directory an
N-body ``file`` is resolved against, which :func:`for_text` makes true of text with no file.
"""

from __future__ import annotations

import os
import re
from typing import List, Tuple

from ._keywords import Generated, Line, Piece
from ._toml import string as toml_string

#: The pointer of a diagnostic: `--> origin:line:column`, a blank gutter, the source line and
#: the carets (see the problem-file library's `Location`).
_LOCATION = re.compile(
    r"^(?P<gutter> *)--> (?P<origin>.*):(?P<line>\d+):(?P<column>\d+)\n"
    r" *\|\n"
    r" *\d+ \| .*\n"
    r" *\| [^\^\n]*(?P<carets>\^+)$",
    re.MULTILINE,
)

#: TOML phrases a keyword user can meet, and the same in keyword terms (applied in order).
_PHRASES: List[Tuple[str, str]] = [
    (r"\[integrator\] needs the length of the run: `steps = \.\.\.` or `t_end = \.\.\.`",
     "the run needs a length: give steps= or t_end="),
    (r"give either `steps` or `t_end` in \[integrator\], not both",
     "give either steps= or t_end=, not both"),
    (r"\[integrator\] needs the time step `h`", "give the time step h="),
    (r"\[initial\] needs the positions `q = \[\.\.\.\]`", "give the initial positions q0=[...]"),
    (r"\[initial\] needs the velocities `v = \[\.\.\.\]` or the momenta `p = \[\.\.\.\]`",
     "give the initial velocities v0=[...] or the momenta p0=[...]"),
    (r"give either `v` or `p` in \[initial\], not both", "give either v0= or p0=, not both"),
    (r"`v` are velocities (.*), `p` momenta", r"v0 are velocities \1, p0 momenta"),
    (r"give the initial state either in `file` or as `q`, `v`/`p`, not both",
     "give the initial state either in bodies_file= or as q0=, v0=/p0=, not both"),
    (r"the problem file has no \[initial\] table", "give the initial state: q0= and v0= (or p0=)"),
    (r"add \[initial\] with `q = \[\.\.\.\]` and `v = \[\.\.\.\]` \(or `p = \[\.\.\.\]`\)",
     "e.g. q0=[1.0], v0=[0.0]"),
    (r"\[system\] needs a `lagrangian` or a `builtin`",
     "give lagrangian=, builtin=, hamiltonian= or discrete_lagrangian="),
    (r"e\.g\. `builtin = \"pendulum\"`; `marsden systems` lists the builtins",
     "e.g. builtin=\"pendulum\"; marsden.systems() lists the builtins"),
    (r"remove `(\w+)` from \[\w+\]", r"leave out \1="),
    (r"`\[sensitivity\]` cannot", "`sensitivity` cannot"),
    (r"give the initial momenta `p = \[\.\.\.\]`", "give the initial momenta p0=[...]"),
    (r"a `(\w+)` needs `coordinates` in \[system\]", r"a `\1` needs coordinates="),
    (r"in \[system\] (\w+)", r"in \1"),
    (r"`v` cannot be used", "`v0` cannot be used"),
    (r"or give `steps`", "or give steps="),
    (r"or give `generator = \[\.\.\.\]`", "or give symmetries={name: [...]}"),
    (r"in \[\[system\.symmetry\]\] (\w+)", r"in the symmetry's \1"),
    (r"`initial\.q`|\binitial\.q\b", "q0"),
    (r"`initial\.v`|\binitial\.v\b", "v0"),
    (r"`initial\.p`|\binitial\.p\b", "p0"),
    (r"`initial\.t0`|\binitial\.t0\b", "t0"),
    (r"the path is relative to the problem file's directory",
     "the path is relative to the working directory"),
]


def for_keywords(message: str, generated: Generated) -> str:
    """``message`` about the text of ``generated``, in keyword terms."""
    match = _LOCATION.search(message)
    if match is not None:
        origin = generated.origins.get(int(match.group("line")))
        pointer = _pointer(origin, int(match.group("column")) - 1, len(match.group("carets")))
        start, end = match.span()
        message = message[:start] + pointer + message[end:]
        message = re.sub(r"\n{2,}", "\n", message).rstrip("\n")
    for pattern, replacement in _PHRASES:
        message = re.sub(pattern, replacement, message)
    return message


def for_text(message: str, origin: str) -> str:
    """``message`` about problem text with no file behind it (``from_toml``): paths in it are
    resolved against the working directory, and the message says so."""
    if not os.path.dirname(origin):
        return message.replace(
            "the path is relative to the problem file's directory",
            "the path is relative to the working directory (from_toml has no file; "
            "Problem.load(path) resolves it relative to the file)")
    return message


def _pointer(origin: "Line | None", column: int, width: int) -> str:
    """Where a keyword problem went wrong: the keyword, and within an expression the
    expression with a caret under the fault."""
    if origin is None:
        return ""
    piece = origin.piece_at(column)
    if piece is None:
        return f"  --> in {origin.keyword}="
    at, span = _inside(piece, column, width)
    return (f"  --> in {piece.label}=\n   |\n   | {piece.source}\n"
            f"   | {' ' * at}{'^' * span}")


def _inside(piece: Piece, column: int, width: int) -> Tuple[int, int]:
    """Character index and width within the expression of a caret at ``column`` of the
    generated line (the literal is the expression quoted, so escapes shift it)."""
    offset = column - piece.column - 1  # after the opening quote
    index = 0
    while index < len(piece.source) and len(toml_string(piece.source[:index])) - 2 < offset:
        index += 1
    index = min(index, max(len(piece.source) - 1, 0))
    return index, max(1, min(width, len(piece.source) - index))
