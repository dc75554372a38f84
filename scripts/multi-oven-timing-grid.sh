#!/usr/bin/env bash
# The timing models on multi-oven bisection, as a sweep (issue #44 item 4; the study is
# sweeps/timing-multi-oven.toml): runs the sweep, then writes its lines and table into
# OUT_DIR. Resumable: finished jobs are skipped.
#
#   bash scripts/multi-oven-timing-grid.sh BIN OUT_DIR
#
# For a cluster: `BIN sweep sweeps/timing-multi-oven.toml --out OUT_DIR --emit slurm`, then
# this script on the finished output (the sweep skips every finished job).
set -euo pipefail
bin=$1 out=$2
cd "$(dirname "$0")/.."
sweep=sweeps/timing-multi-oven.toml
"$bin" sweep "$sweep" --out "$out" --workers "${WORKERS:-2}" --no-report
python3 scripts/timing-study-lines.py multi-oven "$sweep" "$out" > "$out/lines.txt"
python3 scripts/multi-oven-timing-table.py "$out/lines.txt" > "$out/summary.md"
echo "wrote $out/lines.txt, $out/summary.md"
