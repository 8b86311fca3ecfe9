"""The keyword arguments of :class:`marsden.Problem` written as a problem file.

Each keyword is one key of the problem-file schema (the table says which), so everything a
file can say, a keyword can say:

=====================================  ==========================================
keyword                                problem file
=====================================  ==========================================
name, builtin, coordinates,            ``[system]`` (same keys)
parameters, lagrangian, hamiltonian,
discrete_lagrangian, forces,
constraints
rigid_body, potential, torques         ``[system]`` (same keys: a rigid body on SO(3))
gravity, bodies, particles, joints,    ``[system]`` gravity, ``[[system.body]]``,
springs, dampers                       ``[[system.particle]]``, ``[[system.joint]]``,
                                       ``[[system.spring]]``, ``[[system.damper]]``
                                       (jointed bodies and particles)
symmetries, rotation, translation,     ``[[system.symmetry]]``
body_rotation
q0, v0, p0, t0, bodies_file, project   ``[initial]`` q, v, p, t0, file, project
R0, quaternion0, rotation_vector0,     ``[initial]`` R, quaternion, rotation_vector,
Omega0, Pi0                            Omega, Pi
bodies0                                ``[initial.<body>]`` x, v, p, R, quaternion, …
method, h, steps, t_end, tolerance,    ``[integrator]`` (same keys)
max_iterations, fast_paths,
compensated
every, angles, output_dir,             ``[output]`` every, angles, dir, format, plots,
output_format, plots, times,           times, exact_times
exact_times
every_step, certify                    ``[analysis]`` (same keys)
sensitivity                            ``[sensitivity]``
sweep                                  ``[sweep]`` (and ``[sweep.and]``)
=====================================  ==========================================
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Any, Mapping, Optional, Sequence, Union

from . import _bodies
from . import _keywords as kw
from . import _toml
from ._keywords import Generated, Value


@dataclass
class Keywords:
    """The keyword arguments of :class:`marsden.Problem` (``None``: not given)."""

    lagrangian: Any = None
    coordinates: Any = None
    parameters: Optional[Mapping[str, Any]] = None
    q0: Any = None
    v0: Any = None
    p0: Any = None
    method: Optional[str] = None
    h: Optional[float] = None
    steps: Optional[int] = None
    t_end: Optional[float] = None
    forces: Optional[Sequence[Any]] = None
    constraints: Optional[Sequence[Any]] = None
    symmetries: Optional[kw.Symmetries] = None
    hamiltonian: Any = None
    builtin: Optional[str] = None
    discrete_lagrangian: Any = None
    name: Optional[str] = None
    rotation: Union[None, str, Sequence[str]] = None
    translation: Union[None, str, Sequence[str]] = None
    t0: Optional[float] = None
    bodies_file: Any = None
    project: Optional[bool] = None
    tolerance: Optional[float] = None
    max_iterations: Optional[int] = None
    fast_paths: Optional[bool] = None
    compensated: Optional[bool] = None
    every: Optional[int] = None
    angles: Any = None
    output_dir: Any = None
    output_format: Optional[str] = None
    plots: Optional[bool] = None
    times: Optional[Sequence[Any]] = None
    exact_times: Optional[bool] = None
    every_step: Optional[bool] = None
    certify: Optional[bool] = None
    sensitivity: Any = None
    sweep: Optional[Mapping[str, Any]] = None
    rigid_body: Any = None
    potential: Any = None
    torques: Optional[Sequence[Any]] = None
    body_rotation: Union[None, str, Sequence[str]] = None
    gravity: Optional[Sequence[Any]] = None
    bodies: Optional[Sequence[Mapping[str, Any]]] = None
    particles: Optional[Sequence[Mapping[str, Any]]] = None
    joints: Optional[Sequence[Mapping[str, Any]]] = None
    springs: Optional[Sequence[Mapping[str, Any]]] = None
    dampers: Optional[Sequence[Mapping[str, Any]]] = None
    bodies0: Optional[Mapping[str, Mapping[str, Any]]] = None
    R0: Any = None
    quaternion0: Any = None
    rotation_vector0: Any = None
    Omega0: Any = None
    Pi0: Any = None


def write(k: Keywords) -> Generated:
    """The problem file of ``k`` and the keyword behind each of its lines."""
    out = Generated()
    _system(out, k)
    _initial(out, k)
    _integrator(out, k)
    _tables(out, k)
    return out


def _expression(label: str, expr: Any) -> Optional[Value]:
    if expr is None:
        return None
    return Value.string(label, kw.expression(expr, label))


def _expressions(label: str, exprs: Any) -> Optional[Value]:
    if exprs is None:
        return None
    if isinstance(exprs, str) or not hasattr(exprs, "__iter__"):
        exprs = [exprs]  # one expression for one coordinate
    texts = [kw.expression(e, f"{label}[{i}]") for i, e in enumerate(exprs)]
    return Value.strings_of(label, texts)


def _system(out: Generated, k: Keywords) -> None:
    coordinates = kw.maybe(lambda c: _toml.strings(kw.names(c, "coordinates")), k.coordinates)
    out.table("[system]", [
        ("name", "name", kw.maybe(_toml.string, k.name)),
        ("builtin", "builtin", kw.maybe(lambda b: Value.string("builtin", b), k.builtin)),
        ("coordinates", "coordinates", coordinates),
        ("parameters", "parameters", kw.maybe(kw.parameters, k.parameters)),
        ("lagrangian", "lagrangian", _expression("lagrangian", k.lagrangian)),
        ("hamiltonian", "hamiltonian", _expression("hamiltonian", k.hamiltonian)),
        ("discrete_lagrangian", "discrete_lagrangian",
         _expression("discrete_lagrangian", k.discrete_lagrangian)),
        ("forces", "forces", _expressions("forces", k.forces)),
        ("constraints", "constraints", _expressions("constraints", k.constraints)),
        ("rigid_body", "rigid_body", kw.maybe(kw.rigid_body, k.rigid_body)),
        ("potential", "potential", _expression("potential", k.potential)),
        ("torques", "torques", _expressions("torques", k.torques)),
        ("gravity", "gravity", kw.maybe(lambda g: kw.floats(g, "gravity"), k.gravity)),
    ])
    _bodies.system_tables(out, _bodies.Members(k.bodies, k.particles, k.joints, k.springs,
                                               k.dampers))
    for name, generator in kw.symmetry_items(k.symmetries):
        kw.symmetry(out, name, generator)
    kw.named_symmetries(out, "rotation", k.rotation)
    kw.named_symmetries(out, "translation", k.translation)
    kw.named_symmetries(out, "body_rotation", k.body_rotation)


def _initial(out: Generated, k: Keywords) -> None:
    out.table("[initial]", [
        ("t0", "t0", kw.maybe(lambda t: _toml.number(float(t)), k.t0)),
        ("q", "q0", kw.maybe(lambda q: kw.floats(q, "q0"), k.q0)),
        ("v", "v0", kw.maybe(lambda v: kw.floats(v, "v0"), k.v0)),
        ("p", "p0", kw.maybe(lambda p: kw.floats(p, "p0"), k.p0)),
        ("file", "bodies_file", kw.maybe(lambda f: _toml.string(_path(f)), k.bodies_file)),
        ("project", "project", kw.maybe(kw.boolean, k.project)),
        ("R", "R0", kw.maybe(lambda r: kw.matrix_or_vector(r, "R0"), k.R0)),
        ("quaternion", "quaternion0", kw.maybe(lambda q: kw.floats(q, "quaternion0"),
                                                k.quaternion0)),
        ("rotation_vector", "rotation_vector0",
         kw.maybe(lambda v: kw.floats(v, "rotation_vector0"), k.rotation_vector0)),
        ("Omega", "Omega0", kw.maybe(lambda w: kw.floats(w, "Omega0"), k.Omega0)),
        ("Pi", "Pi0", kw.maybe(lambda p: kw.floats(p, "Pi0"), k.Pi0)),
    ])
    _bodies.initial_tables(out, k.bodies0)


def _integrator(out: Generated, k: Keywords) -> None:
    out.table("[integrator]", [
        ("method", "method", kw.maybe(lambda m: Value.string("method", m), k.method)),
        ("h", "h", kw.maybe(lambda h: _toml.number(float(h)), k.h)),
        ("steps", "steps", kw.maybe(_toml.number, k.steps)),
        ("t_end", "t_end", kw.maybe(lambda t: _toml.number(float(t)), k.t_end)),
        ("tolerance", "tolerance", kw.maybe(lambda t: _toml.number(float(t)), k.tolerance)),
        ("max_iterations", "max_iterations", kw.maybe(_toml.number, k.max_iterations)),
        ("fast_paths", "fast_paths", kw.maybe(kw.boolean, k.fast_paths)),
        ("compensated", "compensated", kw.maybe(kw.boolean, k.compensated)),
    ])


def _tables(out: Generated, k: Keywords) -> None:
    """``[output]``, ``[analysis]``, ``[sensitivity]`` and ``[sweep]``, when given."""
    output = [
        ("dir", "output_dir", kw.maybe(lambda d: _toml.string(_path(d)), k.output_dir)),
        ("format", "output_format", kw.maybe(_toml.string, k.output_format)),
        ("every", "every", kw.maybe(_toml.number, k.every)),
        ("plots", "plots", kw.maybe(kw.boolean, k.plots)),
        ("angles", "angles",
         kw.maybe(lambda a: Value.strings_of("angles", kw.names(a, "angles")), k.angles)),
        ("times", "times", kw.maybe(lambda t: kw.floats(t, "times"), k.times)),
        ("exact_times", "exact_times", kw.maybe(kw.boolean, k.exact_times)),
    ]
    if any(value is not None for _, _, value in output):
        out.table("[output]", output)
    analysis = [
        ("every_step", "every_step", kw.maybe(kw.boolean, k.every_step)),
        ("certify", "certify", kw.maybe(kw.boolean, k.certify)),
    ]
    if any(value is not None for _, _, value in analysis):
        out.table("[analysis]", analysis)
    if k.sensitivity is not None:
        kw.sensitivity(out, k.sensitivity)
    if k.sweep is not None:
        kw.sweep(out, k.sweep)


def _path(value: Any) -> str:
    return os.fspath(value)
