#!/usr/bin/env bash
# The timing models on multi-anchor categorization, as sweeps (issue #44 item 4; the study is
# sweeps/timing-multi-anchor.toml, its held-out anchor sets sweeps/timing-multi-anchor-heldout.toml):
# runs the sweep, then writes its lines, the SBF and time-cell runs' simulated boundaries
# (examples/predicted_boundaries.rs) and the table into OUT_DIR. Resumable: finished jobs are
# skipped.
#
#   bash scripts/multi-anchor-timing-grid.sh BIN OUT_DIR [heldout]
#
# For a cluster: `BIN sweep sweeps/timing-multi-anchor.toml --out OUT_DIR --emit slurm`, then
# this script on the finished output (the sweep skips every finished job).
set -euo pipefail
bin=$1 out=$2
cd "$(dirname "$0")/.."
if [[ ${3:-} == heldout ]]; then
  sweep=sweeps/timing-multi-anchor-heldout.toml prefix=heldout-sets-
else
  sweep=sweeps/timing-multi-anchor.toml prefix=
fi
"$bin" sweep "$sweep" --out "$out" --workers "${WORKERS:-2}" --no-report
python3 scripts/timing-study-lines.py multi-anchor "$sweep" "$out" > "$out/${prefix}lines.txt"
cargo build --release --locked --workspace --examples -q
target/release/examples/predicted_boundaries \
  "$out"/MultiAnchor-v0/{sbf,timecells-csc,timecells-ms,timecells-laplace}~*/seed*/run \
  > "$out/${prefix}predicted.txt"
python3 scripts/multi-anchor-timing-table.py "$out/${prefix}lines.txt" "$out/${prefix}predicted.txt" \
  > "$out/${prefix}summary.md"
echo "wrote $out/${prefix}lines.txt, ${prefix}predicted.txt, ${prefix}summary.md"
