"""Problem text (the problem-file grammar, TOML) from Python values.

Keyword arguments become a problem file, which the problem-file library then reads exactly as
it reads a file on disk: the same checks, the same messages, the same numbers. Floats are
written with ``repr`` (the shortest text that reads back to the same double), so no value
changes on the way.
"""

from __future__ import annotations

import json
import math
import numbers
import re
from typing import Any, Iterable, List, Mapping, Sequence

_BARE_KEY = re.compile(r"^[A-Za-z0-9_-]+$")


def string(text: str) -> str:
    """A TOML basic string."""
    return json.dumps(str(text), ensure_ascii=False)


def key(name: str) -> str:
    """A TOML key (quoted unless bare)."""
    return name if _BARE_KEY.match(name) else string(name)


def number(value: Any) -> str:
    """A TOML float (``inf`` and ``nan`` included) or integer, exactly."""
    if isinstance(value, bool):
        raise TypeError(f"expected a number, got {value!r}")
    if isinstance(value, numbers.Integral):
        return str(int(value))
    x = float(value)
    if math.isnan(x):
        return "nan"
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return repr(x)


def floats(values: Iterable[Any]) -> str:
    """A TOML array of floats (integers written as floats)."""
    return "[" + ", ".join(number(float(v)) for v in values) + "]"


def strings(values: Iterable[str]) -> str:
    """A TOML array of strings."""
    return "[" + ", ".join(string(v) for v in values) + "]"


def table(name: str, entries: Sequence[tuple]) -> List[str]:
    """``[name]`` and its ``key = value`` lines (entries whose value is ``None`` left out)."""
    lines = [f"[{name}]"]
    lines += [f"{key(k)} = {v}" for k, v in entries if v is not None]
    return lines


def parameters(values: Mapping[str, Any]) -> str:
    """An inline table of scalar (or list) parameters, in the given order."""
    items = []
    for name, value in values.items():
        if isinstance(value, (list, tuple)) or hasattr(value, "__len__"):
            items.append(f"{key(name)} = {floats(value)}")
        else:
            items.append(f"{key(name)} = {number(float(value))}")
    return "{ " + ", ".join(items) + " }" if items else "{}"


def value(v: Any) -> str:
    """Any value read by ``tomllib`` (numbers, strings, booleans, lists, tables) as TOML text,
    tables inline."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, numbers.Real):
        return number(v)
    if isinstance(v, str):
        return string(v)
    if isinstance(v, Mapping):
        items = [f"{key(k)} = {value(x)}" for k, x in v.items()]
        return "{ " + ", ".join(items) + " }" if items else "{}"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(value(x) for x in v) + "]"
    raise TypeError(f"no TOML form for {type(v).__name__} {v!r}")

