"""``marsden.sweep``: an ensemble of runs of one problem, in process or on any executor."""

from __future__ import annotations

import concurrent.futures
from typing import Any, List, Optional, Sequence, Union

from . import _native, _toml
from ._problem import Problem
from ._solution import Solution

Member = Union[Solution, Exception]


def sweep(
    problem: Problem,
    parameter: Optional[str] = None,
    values: Optional[Sequence[float]] = None,
    executor: Optional[concurrent.futures.Executor] = None,
    *,
    initial: Optional[str] = None,
    every: Optional[int] = None,
    threads: Optional[int] = None,
) -> List[Member]:
    """Runs ``problem`` once per value of a parameter (or of an initial value, ``initial="q[0]"``)
    and returns the members' solutions in the order of ``values``.

    ``executor=None`` runs the members in this process on all cores (``threads`` to choose),
    without the interpreter's lock. Any ``concurrent.futures.Executor`` distributes them
    instead, one task per member: a ``ProcessPoolExecutor``, a Dask cluster's
    ``client.get_executor()``, Ray's or mpi4py's executors. Each member is the problem file
    with the value replaced, run by the same code either way, so the results are identical
    bit for bit.

    A member that fails is reported in its place and the others complete: a run that fails
    part-way is a :class:`Solution` with ``status == "failed"`` (its samples up to the failure
    kept), a value the problem cannot take is a :class:`marsden.ProblemError` in the list.

    >>> sols = marsden.sweep(pendulum, "l", [0.5, 1.0, 2.0])
    >>> from dask.distributed import Client
    >>> sols = marsden.sweep(pendulum, "l", [0.5, 1.0, 2.0], Client().get_executor())
    """
    text = _with_sweep(problem, parameter, initial, values)
    origin = problem._origin
    # The problem's own sweep was checked with the problem; a sweep given here makes other
    # text, checked here.
    own = parameter is None and initial is None
    if executor is None:
        if own:
            results = problem._checked.sweep(every, threads)
        else:
            results = _native.sweep(text, origin, every, threads)
        return [_member(r) for r in results]
    info = problem._info if own else _native.check(text, origin).info
    count = len(info["sweep"][1])
    futures = [executor.submit(_run_member, text, origin, k, every) for k in range(count)]
    return [f.result() for f in futures]


def _with_sweep(problem: Problem, parameter: Optional[str], initial: Optional[str],
                values: Optional[Sequence[float]]) -> str:
    """The problem's text with the sweep table (the problem's own one if none is given)."""
    if parameter is None and initial is None:
        if problem._info.get("sweep") is None:
            raise TypeError("sweep() needs `parameter` (or `initial`) and `values`, or a "
                            "problem with a [sweep] table")
        return problem._text
    if (parameter is None) == (initial is None):
        raise TypeError("give one of `parameter` and `initial`")
    if problem._info.get("sweep") is not None:
        raise TypeError("the problem has its own [sweep] table: call sweep(problem) alone")
    if values is None:
        raise TypeError("sweep() needs `values`")
    target = ("parameter", parameter) if parameter is not None else ("initial", initial)
    lines = _toml.table("sweep", [(target[0], _toml.string(target[1])),
                                  ("values", _toml.floats(values))])
    return problem._text + "\n" + "\n".join(lines) + "\n"


def _member(result: Any) -> Member:
    if isinstance(result, dict):
        return Solution(result)
    if isinstance(result, str):
        return _native.ProblemError(result)
    return KeyboardInterrupt("not run: the sweep was interrupted")


def _run_member(text: str, origin: str, k: int, every: Optional[int]) -> Member:
    """One member, in whichever process the executor chose (importable by name)."""
    try:
        return Solution(_native.member(text, origin, k, every))
    except _native.ProblemError as e:
        return e
