#!/usr/bin/env bash
# Runs the C reference (../shared/bench/verlet.c) and marsden's divan benchmarks in one go and
# prints a table of medians with ratios, so every ratio comes from the same run on the same
# machine. Usage: scripts/bench.sh [bench-name ...]   (default: all benches of the workspace)
set -euo pipefail
cd "$(dirname "$0")/.."
out=target/bench-report
mkdir -p "$out"
verlet_src=${VERLET_C:-../shared/bench/verlet.c}
if [ -f "$verlet_src" ]; then
  gcc -O3 -march=native "$verlet_src" -o target/verlet -lm
  target/verlet pendulum 0.05 1000000 5 > "$out/verlet-pendulum.json"
  target/verlet kepler 0.01 1000000 5 > "$out/verlet-kepler.json"
  target/verlet ho 0.1 1000000 5 > "$out/verlet-ho.json"
else
  echo "note: $verlet_src not found; ratios to verlet.c are omitted" >&2
fi
benches=("$@")
if [ ${#benches[@]} -eq 0 ]; then
  cargo bench --workspace 2>/dev/null | tee "$out/divan.txt"
else
  : > "$out/divan.txt"
  for b in "${benches[@]}"; do
    cargo bench --workspace --bench "$b" 2>/dev/null | tee -a "$out/divan.txt"
  done
fi
python3 scripts/bench_table.py "$out"
