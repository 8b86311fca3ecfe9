"""The keywords of jointed bodies (``gravity``, ``bodies``, ``particles``, ``joints``,
``springs``, ``dampers``, ``bodies0``) written as a multibody problem file: ``[[system.body]]``,
``[[system.particle]]``, ``[[system.joint]]``, ``[[system.spring]]``, ``[[system.damper]]`` and
one ``[initial.<name>]`` per body or particle, each dictionary's keys the file's keys::

    marsden.Problem(
        gravity=[0.0, 0.0, -9.81],
        bodies=[{"name": "a", "mass": 1.0, "inertia": [0.0833, 0.0833, 0.001]}],
        joints=[{"kind": "spherical", "bodies": ["ground", "a"],
                 "at": [[0.0, 0.0, 0.0], [0.0, 0.0, 0.5]]}],
        bodies0={"a": {"x": [0.0, 0.0, -0.5], "Omega": [0.3, 0.0, 2.0]}},
        method="trapezoid", h=0.01, steps=1000)
"""

from __future__ import annotations

import numbers
from typing import Any, Iterable, List, Mapping, NamedTuple, Optional, Sequence, Tuple

from . import _toml
from ._errors import ProblemError
from ._keywords import Generated, Value, boolean

#: The keys of each table, as the problem file has them.
BODY_KEYS = ("name", "mass", "inertia")
PARTICLE_KEYS = ("name", "mass")
JOINT_KEYS = ("name", "kind", "bodies", "at", "axis", "length")
SPRING_KEYS = ("name", "bodies", "at", "stiffness", "rest_length")
DAMPER_KEYS = ("name", "bodies", "at", "coefficient")
INITIAL_KEYS = ("x", "v", "p", "R", "quaternion", "rotation_vector", "Omega", "Pi")


def value(item: Any, label: str) -> Any:
    """A TOML value of a number, a string, a boolean, or a (nested) list of numbers or of
    strings."""
    if isinstance(item, str):
        return Value.string(label, item)
    if isinstance(item, bool):
        return boolean(item)
    if isinstance(item, numbers.Real):
        return _toml.number(float(item))
    if hasattr(item, "__iter__") and not isinstance(item, Mapping):
        entries = list(item)
        if entries and all(isinstance(e, str) for e in entries):
            return Value.strings_of(label, entries)
        parts = [value(e, f"{label}[{i}]") for i, e in enumerate(entries)]
        if any(isinstance(p, Value) and p.strings for p in parts):
            raise ProblemError(f"error: {label}: a list mixes strings and numbers")
        return "[" + ", ".join(p.text if isinstance(p, Value) else p for p in parts) + "]"
    raise ProblemError(f"error: {label}: expected a number, a string or a list, got {item!r}")


def _entries(item: Any, label: str, known: Sequence[str]) -> List[Tuple[str, str, Any]]:
    """One table's lines from a dictionary whose keys are the file's."""
    if not isinstance(item, Mapping):
        raise ProblemError(f"error: {label}: expected a dictionary with keys {list(known)}, "
                           f"got {item!r}")
    unknown = [k for k in item if k not in known]
    if unknown:
        raise ProblemError(f"error: {label}: unknown key(s) {unknown}; the keys are "
                           f"{list(known)}")
    return [(key, f"{label}[{key!r}]", value(item[key], f"{label}[{key!r}]"))
            for key in known if key in item]


def _array_of_tables(out: Generated, header: str, keyword: str, items: Optional[Iterable[Any]],
                     known: Sequence[str]) -> None:
    if items is None:
        return
    if isinstance(items, (Mapping, str)):
        raise ProblemError(f"error: {keyword}: expected a list of dictionaries, got {items!r}")
    for i, item in enumerate(items):
        out.table(header, _entries(item, f"{keyword}[{i}]", known))


class Members(NamedTuple):
    """The keywords of a multibody system's tables, as given."""
    bodies: Any
    particles: Any
    joints: Any
    springs: Any
    dampers: Any


def system_tables(out: Generated, m: Members) -> None:
    """``[[system.body]]``, ``[[system.particle]]``, ``[[system.joint]]``,
    ``[[system.spring]]``, ``[[system.damper]]``."""
    _array_of_tables(out, "[[system.body]]", "bodies", m.bodies, BODY_KEYS)
    _array_of_tables(out, "[[system.particle]]", "particles", m.particles, PARTICLE_KEYS)
    _array_of_tables(out, "[[system.joint]]", "joints", m.joints, JOINT_KEYS)
    _array_of_tables(out, "[[system.spring]]", "springs", m.springs, SPRING_KEYS)
    _array_of_tables(out, "[[system.damper]]", "dampers", m.dampers, DAMPER_KEYS)


def initial_tables(out: Generated, bodies0: Optional[Mapping[str, Any]]) -> None:
    """One ``[initial.<name>]`` per body of ``bodies0 = {name: {"x": …, "R": …, …}}``."""
    if bodies0 is None:
        return
    if not isinstance(bodies0, Mapping):
        raise ProblemError("error: bodies0: expected a dictionary {body name: {\"x\": ..., "
                           f"\"R\": ..., ...}}, got {bodies0!r}")
    for name, data in bodies0.items():
        label = f"bodies0[{name!r}]"
        out.table(f"[initial.{_toml.key(str(name))}]", _entries(data, label, INITIAL_KEYS))
