#!/usr/bin/env bash
# The guide (docs/guide, mkdocs.yml): installs MkDocs, the Material theme, mkdocstrings and
# pymdown-extensions into a virtual environment and builds the site with `mkdocs build
# --strict` into target/guide (a broken include, link or API reference is an error). Needs no
# compile: the Python API page reads crates/marsden-py/python statically.
#
#   scripts/guide.sh              # VENV=target/guide-venv by default; open target/guide/index.html
#   scripts/guide.sh serve        # a live preview on http://127.0.0.1:8000
set -euo pipefail
cd "$(dirname "$0")/.."
PYTHON="${PYTHON:-python3}"
VENV="${VENV:-target/guide-venv}"
start=$(date +%s)
if [ ! -x "$VENV/bin/mkdocs" ]; then
    "$PYTHON" -m venv "$VENV"
    "$VENV/bin/python" -m pip install --quiet --upgrade pip
    "$VENV/bin/python" -m pip install --quiet "mkdocs>=1.6,<2" "mkdocs-material>=9.5,<10" \
        "mkdocstrings[python]>=0.26" "pymdown-extensions>=10.7"
fi
if [ "${1:-}" = "serve" ]; then
    exec "$VENV/bin/mkdocs" serve
fi
NO_MKDOCS_2_WARNING=1 "$VENV/bin/mkdocs" build --strict --quiet
"$VENV/bin/python" scripts/guide_check.py target/guide
echo "guide: built target/guide in $(( $(date +%s) - start )) s"
