"""marsden: variational integrators for Lagrangian mechanics, from Python.

Write a Lagrangian once — as a string in the problem-file grammar or as a SymPy expression —
and simulate it with a structure-preserving (symplectic, momentum-conserving) integrator; the
integration runs in Rust, with no Python in the loop::

    >>> import marsden
    >>> pendulum = marsden.Problem(
    ...     lagrangian="0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)",
    ...     coordinates=["theta"], parameters={"m": 1.0, "l": 1.0, "g": 9.81},
    ...     q0=[1.5], v0=[0.0], method="midpoint", h=0.01, t_end=100.0)
    >>> solution = pendulum.solve()
    >>> solution.q[-1], solution.summary["energy"]["max_rel_error"]

Problem files work too (``marsden.Problem.load("examples/pendulum.toml")``), the catalog is
``marsden.systems()``, and ``marsden.sweep`` runs ensembles on all cores or on any
``concurrent.futures`` executor (Dask, Ray, MPI).
"""

from __future__ import annotations

from importlib import metadata
from typing import Any, Dict, List

from . import _native
from ._errors import ProblemError, SimulationError
from ._optimize import OptimalControl, OptimalControlSolution
from ._problem import Problem
from ._resume import resume
from ._sensitivity import Sensitivity
from ._simulation import Simulation
from ._solution import Body, Solution
from ._sweep import sweep
from ._sympy import to_grammar

__all__ = [
    "__version__",
    "Body",
    "OptimalControl",
    "OptimalControlSolution",
    "Problem",
    "ProblemError",
    "Sensitivity",
    "Simulation",
    "SimulationError",
    "Solution",
    "resume",
    "sweep",
    "systems",
    "to_grammar",
]


def _version() -> str:
    """The installed package's version (maturin takes it from Cargo: the workspace's)."""
    try:
        return metadata.version("marsden")
    except metadata.PackageNotFoundError:  # imported from a source tree, not installed
        return "0+unknown"


#: The version of marsden (the same as the ``marsden`` command's, ``marsden --version``).
__version__: str = _version()


def systems() -> List[Dict[str, Any]]:
    """The catalog of built-in systems: for each, ``name``, ``summary``, ``coordinates``,
    ``parameters`` (name -> default), ``lagrangian`` (a formula in the grammar) and ``text``
    (what ``marsden systems`` prints).

    >>> [s["name"] for s in marsden.systems()]
    ['harmonic_oscillator', 'free_fall', 'pendulum', 'double_pendulum', 'kepler', ...]
    """
    entries = []
    for s in _native.systems():
        entry = dict(s)
        entry["parameters"] = dict(entry["parameters"])
        entries.append(entry)
    return entries
