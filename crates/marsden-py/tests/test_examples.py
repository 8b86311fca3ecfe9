"""The Python examples run as a user would run them (each file of examples/python/, as a
script in a fresh interpreter), and say what they promise."""

from __future__ import annotations

import ast
import functools
import importlib.util
import pathlib
import re
import subprocess
import sys
import tempfile
from typing import List

import pytest

from conftest import EXAMPLES

SCRIPTS = sorted((EXAMPLES / "python").glob("*.py"))

#: Longest an example may take (the extension is built in the dev profile in CI).
TIME_LIMIT = 300


def required_modules(script: pathlib.Path) -> List[str]:
    """The top-level packages a script imports unconditionally (imports inside ``try``
    are optional by construction)."""
    names = []
    for node in ast.parse(script.read_text(encoding="utf-8")).body:
        if isinstance(node, ast.Import):
            names += [a.name.split(".")[0] for a in node.names]
        elif isinstance(node, ast.ImportFrom) and node.module and not node.level:
            names.append(node.module.split(".")[0])
    return sorted(set(names))


@functools.lru_cache(maxsize=None)
def run_example(name: str) -> subprocess.CompletedProcess:
    """Runs ``examples/python/<name>`` once (in a scratch directory: examples may write
    files); skips it if it needs a package that is not installed."""
    script = EXAMPLES / "python" / name
    missing = [m for m in required_modules(script) if importlib.util.find_spec(m) is None]
    if missing:
        pytest.skip(f"{name} needs {', '.join(missing)}, which is not installed")
    with tempfile.TemporaryDirectory() as scratch:
        return subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                              timeout=TIME_LIMIT, cwd=scratch)


def test_the_examples_are_found():
    assert {s.name for s in SCRIPTS} >= {"pendulum.py", "kepler_sympy.py", "fit_scipy.py",
                                          "sweep_dask.py"}


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda s: s.name)
def test_every_python_example_runs_to_completion(script):
    done = run_example(script.name)
    assert done.returncode == 0, f"{script.name} failed:\n{done.stdout}\n{done.stderr}"


def test_an_example_needs_only_its_unconditional_imports(tmp_path):
    """What decides a skip: imports inside `try` are optional, the others required."""
    script = tmp_path / "needs.py"
    script.write_text("import os\nimport surely_not_installed_xyz.sub\n"
                      "try:\n    import also_missing\nexcept ImportError:\n    pass\n")
    assert required_modules(script) == ["os", "surely_not_installed_xyz"]


def test_the_least_squares_fit_recovers_stiffness_and_damping():
    out = run_example("fit_scipy.py").stdout
    fitted = re.search(r"fitted = \(([-0-9.]+), ([-0-9.]+)\)", out)
    assert fitted, out
    k, c = float(fitted.group(1)), float(fitted.group(2))
    # Noise of 0.01 on 51 samples: the fit lands within a few hundredths of (4, 0.3).
    assert abs(k - 4.0) < 0.02 and abs(c - 0.3) < 0.02, out


def test_the_kepler_example_keeps_angular_momentum_r10():
    """R10 (Kepler, e = 0.6): L_z = √(1 − e²) = 0.8, conserved by a rotation-invariant L_d
    (discrete Noether) to 1e-12; the example runs ten whole periods."""
    out = run_example("kepler_sympy.py").stdout
    found = re.search(r"L_z = ([-0-9.]+), max drift ([-0-9.e+]+)", out)
    assert found, out
    assert abs(float(found.group(1)) - 0.8) < 1e-14, out
    assert float(found.group(2)) < 1e-12, out
    assert "completed" in out and "601 samples" in out, out  # 6000 steps, every 10th


def test_the_dask_example_matches_the_in_process_sweep():
    out = run_example("sweep_dask.py").stdout
    lines = [line for line in out.splitlines() if line.startswith("l =")]
    assert len(lines) == 16 and all(line.endswith("identical: True") for line in lines), out
