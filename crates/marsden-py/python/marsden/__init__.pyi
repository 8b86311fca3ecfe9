"""Type stubs of the marsden package."""

import concurrent.futures
import os
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

Expression = Any  # a string in the problem-file grammar, or a SymPy expression
Symmetries = Union[Mapping[str, Sequence[Expression]], Sequence[Tuple[str, Sequence[Expression]]]]
FloatArray = npt.NDArray[np.float64]

__all__ = ["Problem", "ProblemError", "Sensitivity", "SimulationError", "Solution", "sweep",
           "systems", "to_grammar"]

SensitivityRequest = Union[bool, Sequence[str], Mapping[str, Any]]

class ProblemError(ValueError):
    """A problem that cannot run; the message is the ``marsden`` command's, with a caret."""

class SimulationError(RuntimeError):
    """A run that failed part-way; ``.solution`` holds the samples before the failure."""
    solution: Solution
    def __init__(self, message: str, solution: Solution) -> None: ...

class Sensitivity:
    """The Jacobians ``∂(q_k, p_k)/∂(columns)`` of a run (initial state and parameters)."""
    rows: List[str]
    columns: List[str]
    final: FloatArray
    t: FloatArray
    jacobians: FloatArray
    note: Optional[str]
    def __init__(self, block: Dict[str, Any], arrays: Dict[str, Any]) -> None: ...
    def column(self, name: str) -> FloatArray: ...

class Solution:
    """The stored samples of a run, one row per sample, and its summary."""
    coordinates: List[str]
    t: FloatArray
    q: FloatArray
    p: FloatArray
    v: FloatArray
    energy: FloatArray
    momenta: Dict[str, FloatArray]
    constraint_residual: Optional[FloatArray]
    multipliers: FloatArray
    summary: Dict[str, Any]
    status: str
    error: Optional[str]
    warnings: List[str]
    sensitivity: Optional[Sensitivity]
    def __init__(self, fields: Dict[str, Any]) -> None: ...
    def __len__(self) -> int: ...
    @property
    def ok(self) -> bool: ...
    def final_state(self) -> Dict[str, Any]: ...
    def to_pandas(self) -> Any: ...
    def plot(self, ax: Any = ...) -> Any: ...

class Problem:
    """A mechanical system, its initial state and the integrator: a problem file."""
    def __init__(
        self,
        lagrangian: Optional[Expression] = ...,
        coordinates: Optional[Sequence[Any]] = ...,
        parameters: Optional[Mapping[str, Any]] = ...,
        q0: Optional[Sequence[float]] = ...,
        v0: Optional[Sequence[float]] = ...,
        p0: Optional[Sequence[float]] = ...,
        method: Optional[str] = ...,
        h: Optional[float] = ...,
        steps: Optional[int] = ...,
        t_end: Optional[float] = ...,
        forces: Optional[Sequence[Expression]] = ...,
        constraints: Optional[Sequence[Expression]] = ...,
        symmetries: Optional[Symmetries] = ...,
        hamiltonian: Optional[Expression] = ...,
        *,
        builtin: Optional[str] = ...,
        name: Optional[str] = ...,
        t0: Optional[float] = ...,
        tolerance: Optional[float] = ...,
        max_iterations: Optional[int] = ...,
        project: Optional[bool] = ...,
        fast_paths: Optional[bool] = ...,
        compensated: Optional[bool] = ...,
        every: Optional[int] = ...,
    ) -> None: ...
    @classmethod
    def from_toml(cls, text: str, origin: str = ...) -> Problem: ...
    @classmethod
    def load(cls, path: Union[str, os.PathLike[str]]) -> Problem: ...
    @classmethod
    def builtin(cls, name: str, **kwargs: Any) -> Problem: ...
    @property
    def toml(self) -> str: ...
    @property
    def name(self) -> str: ...
    @property
    def coordinates(self) -> List[str]: ...
    @property
    def parameters(self) -> Dict[str, float]: ...
    @property
    def method(self) -> str: ...
    @property
    def h(self) -> float: ...
    @property
    def steps(self) -> int: ...
    def solve(self, every: Optional[int] = ..., progress: bool = ...,
              sensitivity: Optional[SensitivityRequest] = ...) -> Solution: ...

def sweep(
    problem: Problem,
    parameter: Optional[str] = ...,
    values: Optional[Sequence[float]] = ...,
    executor: Optional[concurrent.futures.Executor] = ...,
    *,
    initial: Optional[str] = ...,
    every: Optional[int] = ...,
    threads: Optional[int] = ...,
) -> List[Union[Solution, Exception]]: ...
def systems() -> List[Dict[str, Any]]: ...
def to_grammar(expr: Any) -> str: ...
