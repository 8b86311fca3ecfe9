#!/usr/bin/env python3
"""Checks the built guide (target/guide, from scripts/guide.sh): every <img> of every page
exists, each page that includes an example shows it (the file's first line is in the HTML),
the Python API page documents `Problem`, and no page is left with an unexpanded `--8<--`.

    python3 scripts/guide_check.py [target/guide]
"""

from __future__ import annotations

import html
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
SOURCE = ROOT / "docs" / "guide"


def main() -> int:
    site = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "target" / "guide"
    problems: list[str] = []
    pages = 0
    for md in sorted(SOURCE.rglob("*.md")):
        page = md.relative_to(SOURCE).with_suffix("")
        built = site / page / "index.html" if page.name != "index" else site / page.with_suffix(".html")
        if not built.exists():
            problems.append(f"{page}: not built ({built})")
            continue
        pages += 1
        text = built.read_text(encoding="utf-8")
        plain = html.unescape(re.sub(r"<[^>]+>", "", text))
        for src in re.findall(r'<img[^>]*src="([^"]+)"', text):
            if src.startswith(("http://", "https://", "data:")):
                continue
            if not (built.parent / src).resolve().exists():
                problems.append(f"{page}: missing picture {src}")
        if re.search(r"--8<-- *\"", plain):
            problems.append(f"{page}: an unexpanded snippet")
        for name in re.findall(r'--8<-- "([^"]+)"', md.read_text(encoding="utf-8")):
            first = (SOURCE / "examples" / name).read_text(encoding="utf-8").splitlines()[0]
            if first.strip() not in plain:
                problems.append(f"{page}: does not show {name} ({first[:40]!r}…)")
    api = (site / "reference" / "python" / "index.html").read_text(encoding="utf-8")
    if "marsden.Problem" not in api and "Problem" not in api:
        problems.append("reference/python: no Problem in the API page")
    for p in problems:
        print("guide:", p, file=sys.stderr)
    print(f"guide_check: {pages} pages, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
