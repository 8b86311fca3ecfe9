"""The guide's Python examples (docs/guide/examples/python/): each file runs, and the numbers it
leaves in its ``result`` dictionary are those docs/guide/examples/expected.toml quotes, each with
its independent reason (a reference case, a closed form or a bound)."""

from __future__ import annotations

import math
import runpy
import tomllib

import pytest

from conftest import ROOT

GUIDE = ROOT / "docs" / "guide" / "examples"


def _checks() -> list[dict]:
    with open(GUIDE / "expected.toml", "rb") as f:
        return tomllib.load(f)["python"]


@pytest.fixture(scope="module")
def results() -> dict:
    """Runs every guide Python file once; file name → its ``result`` dictionary."""
    return {}


def _result(results: dict, name: str) -> dict:
    if name not in results:
        namespace = runpy.run_path(str(GUIDE / name), run_name="__main__")
        results[name] = namespace["result"]
    return results[name]


@pytest.mark.parametrize("check", _checks(), ids=lambda c: f"{c['file']}:{c['key']}")
def test_guide_python_numbers_match_reference_cases(check: dict, results: dict) -> None:
    """R1, R8, R10 and the swing-up's independent optimum, as the guide's pages quote them."""
    assert check.get("reason"), "every expected value says why"
    found = _result(results, check["file"])[check["key"]]
    if "max" in check:
        assert abs(found) <= check["max"], (found, check["reason"])
    else:
        tol = check["abs"] if "abs" in check else check["rel"] * abs(check["value"])
        assert math.isfinite(found) and abs(found - check["value"]) <= tol, (found, check["reason"])


def test_every_guide_python_file_is_checked() -> None:
    """No page shows a Python file that CI does not run."""
    checked = {c["file"] for c in _checks()}
    for path in sorted((GUIDE / "python").glob("*.py")):
        assert f"python/{path.name}" in checked, path.name
