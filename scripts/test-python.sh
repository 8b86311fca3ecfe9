#!/usr/bin/env bash
# The Python package's tests: builds and installs crates/marsden-py into a fresh virtual
# environment with pytest, numpy, sympy, scipy, matplotlib and dask[distributed], then runs
# crates/marsden-py/tests. The extension is built with the `dev` profile (`pip install` gives
# users `release`): what `cargo test --workspace` compiled into target/debug is reused, the
# workspace crates included (marsden-py's Cargo.toml names the features a build of it alone
# would otherwise resolve differently), and the suite runs in seconds at that level (the bits are the same in every profile). The
# bit-for-bit comparisons with the `marsden` command use $MARSDEN_BIN, else
# target/{release,debug}/marsden (built if missing).
#
#   scripts/test-python.sh            # VENV=target/ci-venv by default
#   PYTHON=python3.12 scripts/test-python.sh -k sweep
set -euo pipefail
cd "$(dirname "$0")/.."
PYTHON="${PYTHON:-python3}"
VENV="${VENV:-target/ci-venv}"
rm -rf "$VENV"
"$PYTHON" -m venv "$VENV"
"$VENV/bin/python" -m pip install --quiet --upgrade pip
"$VENV/bin/python" -m pip install --quiet pytest numpy sympy "dask[distributed]" pandas scipy matplotlib
start=$(date +%s)
MATURIN_PEP517_ARGS="--profile dev" "$VENV/bin/python" -m pip install --quiet ./crates/marsden-py
echo "test-python: built and installed the extension in $(( $(date +%s) - start )) s"
if [ -z "${MARSDEN_BIN:-}" ] && [ ! -x target/debug/marsden ] && [ ! -x target/release/marsden ]; then
    cargo build -p marsden-cli
fi
cd crates/marsden-py/tests
"../../../$VENV/bin/python" -m pytest -q "$@"
