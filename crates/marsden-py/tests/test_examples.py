"""The Python examples run as a user would run them, and say what they promise."""

from __future__ import annotations

import re
import subprocess
import sys

import pytest

from conftest import EXAMPLES


def run_example(name: str) -> str:
    done = subprocess.run([sys.executable, str(EXAMPLES / "python" / name)], check=True,
                          capture_output=True, text=True, timeout=600)
    return done.stdout


def test_the_least_squares_fit_recovers_stiffness_and_damping():
    pytest.importorskip("scipy")
    out = run_example("fit_scipy.py")
    fitted = re.search(r"fitted = \(([-0-9.]+), ([-0-9.]+)\)", out)
    assert fitted, out
    k, c = float(fitted.group(1)), float(fitted.group(2))
    # Noise of 0.01 on 51 samples: the fit lands within a few hundredths of (4, 0.3).
    assert abs(k - 4.0) < 0.02 and abs(c - 0.3) < 0.02, out
