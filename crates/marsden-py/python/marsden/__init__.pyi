"""Type stubs of the marsden package."""

import concurrent.futures
import os
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

Expression = Any  # a string in the problem-file grammar, a SymPy expression or a number
#: A generator (one expression per coordinate) or a named symmetry ({"rotation": "z"}).
Generator = Union[Sequence[Expression], Mapping[str, str]]
Symmetries = Union[Mapping[str, Generator], Sequence[Tuple[str, Generator]]]
ProgressRequest = Union[bool, Callable[[int, int, float, bool], Any]]
PathLike = Union[str, os.PathLike[str]]
FloatArray = npt.NDArray[np.float64]

__version__: str

__all__ = ["__version__", "OptimalControl", "OptimalControlSolution", "Problem", "ProblemError", "Sensitivity",
           "SimulationError",
           "Solution", "sweep", "systems", "to_grammar"]

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
    energy: Optional[FloatArray]
    momenta: Dict[str, FloatArray]
    constraint_residual: Optional[FloatArray]
    multipliers: FloatArray
    R: Optional[FloatArray]
    Pi: Optional[FloatArray]
    summary: Dict[str, Any]
    status: str
    error: Optional[str]
    warnings: List[str]
    sensitivity: Optional[Sensitivity]
    observables: Dict[str, FloatArray]
    events: Dict[str, Dict[str, FloatArray]]
    at_times: Optional[Dict[str, Any]]
    def __init__(self, fields: Dict[str, Any]) -> None: ...
    def __len__(self) -> int: ...
    @property
    def ok(self) -> bool: ...
    @property
    def quaternion(self) -> Optional[FloatArray]: ...
    def final_state(self) -> Dict[str, Any]: ...
    def to_pandas(self) -> Any: ...
    def plot(self, ax: Any = ...) -> Any: ...

class OptimalControlSolution:
    """The optimal (or last) trajectory, its controls (``u`` at the times ``t_u``) and summary."""
    coordinates: List[str]
    controls: List[str]
    t: FloatArray
    q: FloatArray
    p: FloatArray
    u: FloatArray
    t_u: FloatArray
    cost: float
    status: str
    summary: Dict[str, Any]
    @property
    def converged(self) -> bool: ...

class OptimalControl:
    """An optimal control problem (DMOC) on a problem's system, from keywords."""
    problem: Problem
    def __init__(
        self,
        problem: Problem,
        cost: Expression,
        t_end: float,
        steps: int,
        start: Mapping[str, Sequence[Any]],
        end: Mapping[str, Sequence[Any]],
        *,
        controls: Optional[Sequence[str]] = ...,
        forces: Optional[Sequence[Expression]] = ...,
        final_cost: Optional[Expression] = ...,
        t0: Optional[float] = ...,
        method: Optional[str] = ...,
        bounds: Optional[Mapping[str, Sequence[float]]] = ...,
        path: Optional[Sequence[Expression]] = ...,
        guess: Optional[str] = ...,
        tolerance: Optional[float] = ...,
        constraint_tolerance: Optional[float] = ...,
        max_iterations: Optional[int] = ...,
    ) -> None: ...
    @property
    def toml(self) -> str: ...
    def solve(self) -> OptimalControlSolution: ...

class Problem:
    """A mechanical system, its initial state and the integrator: a problem file."""
    def __init__(
        self,
        lagrangian: Optional[Expression] = ...,
        coordinates: Optional[Union[str, Sequence[Any]]] = ...,
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
        discrete_lagrangian: Optional[Expression] = ...,
        name: Optional[str] = ...,
        rotation: Optional[Union[str, Sequence[str]]] = ...,
        translation: Optional[Union[str, Sequence[str]]] = ...,
        t0: Optional[float] = ...,
        bodies_file: Optional[PathLike] = ...,
        project: Optional[bool] = ...,
        tolerance: Optional[float] = ...,
        max_iterations: Optional[int] = ...,
        fast_paths: Optional[bool] = ...,
        compensated: Optional[bool] = ...,
        every: Optional[int] = ...,
        angles: Optional[Union[str, Sequence[Any]]] = ...,
        output_dir: Optional[PathLike] = ...,
        output_format: Optional[str] = ...,
        plots: Optional[bool] = ...,
        times: Optional[Sequence[float]] = ...,
        exact_times: Optional[bool] = ...,
        every_step: Optional[bool] = ...,
        certify: Optional[bool] = ...,
        sensitivity: Optional[SensitivityRequest] = ...,
        sweep: Optional[Mapping[str, Any]] = ...,
        rigid_body: Optional[Any] = ...,
        potential: Optional[Expression] = ...,
        torques: Optional[Sequence[Expression]] = ...,
        body_rotation: Optional[Union[str, Sequence[str]]] = ...,
        R0: Optional[Any] = ...,
        quaternion0: Optional[Sequence[float]] = ...,
        rotation_vector0: Optional[Sequence[float]] = ...,
        Omega0: Optional[Sequence[float]] = ...,
        Pi0: Optional[Sequence[float]] = ...,
        gravity: Optional[Sequence[float]] = ...,
        bodies: Optional[Sequence[Mapping[str, Any]]] = ...,
        particles: Optional[Sequence[Mapping[str, Any]]] = ...,
        joints: Optional[Sequence[Mapping[str, Any]]] = ...,
        springs: Optional[Sequence[Mapping[str, Any]]] = ...,
        dampers: Optional[Sequence[Mapping[str, Any]]] = ...,
        bodies0: Optional[Mapping[str, Mapping[str, Any]]] = ...,
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
    @property
    def is_optimal_control(self) -> bool: ...
    def optimize(self) -> OptimalControlSolution: ...
    def simulation(self) -> Simulation: ...
    def solve(self, every: Optional[int] = ..., progress: ProgressRequest = ...,
              sensitivity: Optional[SensitivityRequest] = ...,
              dir: Optional[str] = ..., checkpoint_every: Optional[int] = ...) -> Solution: ...
    def sweep(self, parameter: Optional[str] = ..., values: Optional[Sequence[float]] = ...,
              executor: Optional[concurrent.futures.Executor] = ..., *,
              initial: Optional[str] = ..., every: Optional[int] = ...,
              threads: Optional[int] = ...) -> List[Union[Solution, Exception]]: ...

class Simulation:
    t: float
    q: FloatArray
    p: FloatArray
    steps: int
    def __init__(self, problem: Problem) -> None: ...
    @property
    def state(self) -> Dict[str, Any]: ...
    def step(self, n: int = ...) -> Solution: ...
    def integrate(self, t: float, every: Optional[int] = ...,
                  progress: ProgressRequest = ...) -> Solution: ...
    def save(self, path: Union[str, os.PathLike[str]]) -> None: ...
    @classmethod
    def load(cls, path: Union[str, os.PathLike[str]]) -> Simulation: ...
    @classmethod
    def from_checkpoint(cls, directory: Union[str, os.PathLike[str]]) -> Simulation: ...

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
def resume(dir: Union[str, os.PathLike[str]], progress: ProgressRequest = ...) -> Dict[str, Any]: ...
def to_grammar(expr: Any) -> str: ...
