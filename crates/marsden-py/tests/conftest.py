"""Shared fixtures of the Python tests: the repository's examples and the `marsden` command."""

from __future__ import annotations

import os
import pathlib
import shutil

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]
EXAMPLES = ROOT / "examples"


def marsden_command() -> str | None:
    """The `marsden` binary: $MARSDEN_BIN, else one built in target/, else on the PATH."""
    candidates = [os.environ.get("MARSDEN_BIN")]
    candidates += [str(ROOT / "target" / p / "marsden") for p in ("release", "debug")]
    for c in candidates:
        if c and os.path.isfile(c) and os.access(c, os.X_OK):
            return c
    return shutil.which("marsden")


@pytest.fixture
def cli() -> str:
    command = marsden_command()
    if command is None:
        pytest.skip("no `marsden` binary: build it with `cargo build -p marsden-cli`")
    return command


PENDULUM = dict(
    lagrangian="0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)",
    coordinates=["theta"],
    parameters={"m": 1.0, "l": 1.0, "g": 1.0},
    q0=[1.5],
    v0=[0.0],
    method="midpoint",
    h=0.05,
)
