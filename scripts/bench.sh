#!/usr/bin/env bash
# Runs the C reference (verlet.c, kept beside the repository) and marsden's divan benchmarks in
# one go and prints a table of medians with ratios, so every ratio comes from the same run on the
# same machine. Usage: scripts/bench.sh [bench-name ...]
#   default: the core benches step, constrained, nbody, chain (crates/marsden/benches/)
# Environment: VERLET_C (path of verlet.c), BENCH_DATA (directory of the Plummer files).
set -euo pipefail
cd "$(dirname "$0")/.."
out=target/bench-report
mkdir -p "$out"
rm -f "$out"/divan-*.txt "$out"/verlet-*.json
verlet_src=${VERLET_C:-../shared/bench/verlet.c}
data=${BENCH_DATA:-../shared/bench/data}
benches=("$@")
if [ ${#benches[@]} -eq 0 ]; then
  benches=(step constrained nbody chain)
fi
# Build everything first, so the timed runs are not disturbed by our own compiler.
cargo bench -p marsden "${benches[@]/#/--bench=}" --no-run 2>/dev/null
if [ -f "$verlet_src" ]; then
  gcc -O3 -march=native "$verlet_src" -o target/verlet -lm
  target/verlet pendulum 0.05 1000000 5 > "$out/verlet-pendulum.json"
  target/verlet kepler 0.01 1000000 5 > "$out/verlet-kepler.json"
  target/verlet ho 0.1 1000000 5 > "$out/verlet-ho.json"
  if [[ " ${benches[*]} " == *" nbody "* ]]; then
    # N-body, kernel "full" (all ordered pairs, vectorised): G = 1, eps = 0.01, h = 1e-3;
    # steps per repeat chosen for about 0.2 s.
    for spec in 64:20000 256:2000 1024:100; do
      n=${spec%%:*}; steps=${spec##*:}
      file="$data/plummer_N${n}_seed20241121.txt"
      [ -f "$file" ] && target/verlet nbody "$file" 1 0.01 0.001 "$steps" 5 "$steps" full \
        > "$out/verlet-nbody-$n.json"
    done
  fi
else
  echo "note: $verlet_src not found; ratios to verlet.c are omitted" >&2
fi
for b in "${benches[@]}"; do
  MARSDEN_BENCH_DATA="$(realpath "$data" 2>/dev/null || echo "$data")" \
    cargo bench -p marsden --bench "$b" 2>/dev/null | tee "$out/divan-$b.txt"
done
python3 scripts/bench_table.py "$out"
