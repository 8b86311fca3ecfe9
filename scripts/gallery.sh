#!/usr/bin/env bash
# Redraws the README's gallery (docs/gallery/*.png): one picture of each plot kind, each from a
# problem file in examples/. Needs pngquant (`apt-get install pngquant`), which keeps each
# picture near 50 KB. MARSDEN=path/to/marsden uses that binary instead of a release build.
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ -z "${MARSDEN:-}" ]]; then
    cargo build --release -p marsden-cli
    MARSDEN=target/release/marsden
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
run() { "$MARSDEN" run "examples/$1.toml" --out "$tmp/$1" --quiet "${@:2}"; }
run nbody
run double_pendulum --steps 4000
run kepler
run damped_oscillator
run cartesian_pendulum
run pendulum_sweep
run heavy_top
run free_rigid_body
mkdir -p docs/gallery
pick() { pngquant 16 --speed 1 --force --output "docs/gallery/$3" "$tmp/$1/$2"; }
pick nbody configuration.png configuration.png
pick double_pendulum phase_portrait.png phase_portrait.png
pick double_pendulum time_series.png time_series.png
pick kepler energy_error.png energy_error.png
pick kepler momentum_drift.png momentum_drift.png
pick damped_oscillator energy_balance.png energy_balance.png
pick cartesian_pendulum constraint_residual.png constraint_residual.png
pick cartesian_pendulum multipliers.png multipliers.png
pick pendulum_sweep sweep.png sweep.png
pick heavy_top axis_tip.png axis_tip.png
pick free_rigid_body body_momentum.png body_momentum.png
du -ch docs/gallery/*.png | tail -1
