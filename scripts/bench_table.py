"""Turns divan's text output and verlet.c's JSON into a markdown table of medians and ratios.

Reads target/bench-report/divan-<bench>.txt (one file per bench binary) and verlet-*.json, all
written by scripts/bench.sh in one run. Rows are `<bench>/<path>`; the ratio column divides by
the matching verlet.c run of the same invocation. Rows of a `*_run1000` group time 1000 steps
and are shown per step. For the chain bench it also fits the exponent
a of `median ∝ n^a` (least squares in log-log).
"""
import json
import math
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


def reference(bench: str, name: str, refs: dict[str, float | None]) -> float | None:
    """The verlet.c run a row compares with."""
    parts = name.split("/")
    if bench == "nbody" and parts[0] == "trapezoid":
        return refs.get(f"nbody-{parts[-1]}")
    if bench == "step":
        group = parts[0]
        for k in ("pendulum", "kepler", "ho"):
            if group.startswith(k + "_h"):
                return refs.get(k)
    return None


def fit_exponent(points: list[tuple[float, float]]) -> float:
    xs = [math.log(n) for n, _ in points]
    ys = [math.log(t) for _, t in points]
    mx, my = statistics.fmean(xs), statistics.fmean(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def main(out: str) -> None:
    d = pathlib.Path(out)
    refs = {p.stem.removeprefix("verlet-"): verlet_ns(p) for p in sorted(d.glob("verlet-*.json"))}
    print("| benchmark | median | × verlet.c (same run) | vs trep |")
    print("|---|---|---|---|")
    chain: list[tuple[float, float]] = []
    for path in sorted(d.glob("divan-*.txt")):
        bench = path.stem.removeprefix("divan-")
        for name, ns in divan_rows(path.read_text()):
            if name.split("/")[0].endswith("_run1000"):
                ns /= 1000.0  # runs of 1000 steps: per step
            ref = reference(bench, name, refs)
            ratio = f"{ns / ref:.2f}×" if ref else "–"
            trep = next((TREP[k] for k in TREP if name.startswith(k + "_h") or name.startswith(k + "/")), None)
            vs = f"{trep / ns:.0f}× faster" if trep else "–"
            shown = f"{ns / 1e6:.3f} ms" if ns >= 1e6 else f"{ns / 1e3:.2f} µs" if ns >= 1e4 else f"{ns:.1f} ns"
            print(f"| {bench}/{name} | {shown} | {ratio} | {vs} |")
            if bench == "chain" and name.split("/")[-1].isdigit():
                chain.append((float(name.split("/")[-1]), ns))
    for k, v in refs.items():
        if v:
            shown = f"{v / 1e6:.3f} ms" if v >= 1e6 else f"{v:.1f} ns"
            print(f"| verlet.c {k} | {shown} | 1× | – |")
    if len(chain) >= 2:
        chain.sort()
        a = fit_exponent(chain)
        per = ", ".join(f"n={int(n)}: {t / n:.1f} ns/particle" for n, t in chain)
        print(f"\nchain midpoint: cost ∝ n^{a:.3f} over n = {int(chain[0][0])} … {int(chain[-1][0])} ({per})")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "target/bench-report")
