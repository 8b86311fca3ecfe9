"""Turns divan's text output and verlet.c's JSON into a markdown table of medians and ratios."""
import json
import pathlib
import re
import statistics
import sys

UNITS = {"ps": 1e-3, "ns": 1.0, "µs": 1e3, "us": 1e3, "ms": 1e6, "s": 1e9}
TREP = {"pendulum": 6570.0, "double_pendulum": 14900.0, "constrained_pendulum": 8240.0}


def verlet_ns(path: pathlib.Path) -> float | None:
    if not path.exists():
        return None
    data = json.loads(path.read_text())
    return statistics.median(data["times"]) / data["n"] * 1e9


def divan_rows(text: str):
    """Yields (bench path, median ns) from divan's tree output."""
    stack: list[tuple[int, str]] = []
    for line in text.splitlines():
        m = re.match(r"^([│ ]*)[├╰]─ (\S+)(.*)$", line)
        if not m:
            continue
        depth = len(m.group(1)) // 3
        stack = [s for s in stack if s[0] < depth] + [(depth, m.group(2))]
        cells = [c.strip() for c in m.group(3).split("│")]
        if len(cells) < 3 or not cells[2]:
            continue
        value, unit = cells[2].split()
        yield "/".join(name for _, name in stack), float(value) * UNITS[unit]


def main(out: str) -> None:
    d = pathlib.Path(out)
    refs = {name: verlet_ns(d / f"verlet-{name}.json") for name in ("pendulum", "kepler", "ho")}
    print("| benchmark | median | × verlet.c (same run) | vs trep |")
    print("|---|---|---|---|")
    for name, ns in divan_rows((d / "divan.txt").read_text()):
        group = name.split("/")[0]
        ref = next((refs[k] for k in refs if refs[k] and group.startswith(k + "_h")), None)
        ratio = f"{ns / ref:.1f}×" if ref else "–"
        trep = next((TREP[k] for k in TREP if name.startswith(k + "_h") or name.startswith(k + "/")), None)
        vs = f"{trep / ns:.0f}× faster" if trep else "–"
        print(f"| {name} | {ns:.1f} ns | {ratio} | {vs} |")
    for k, v in refs.items():
        if v:
            print(f"| verlet.c {k} | {v:.1f} ns | 1× | – |")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "target/bench-report")
