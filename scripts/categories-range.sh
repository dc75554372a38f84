#!/usr/bin/env bash
# Unit categories of the timing models at every FI TD of the paper, as a sweep (the study is
# sweeps/categories-range.toml): runs the sweep, then writes one line per model, seed, TD
# and population (its units and category counts) into OUT_DIR/lines.txt. Resumable:
# finished jobs are skipped. On a cluster: `chronocooked sweep sweeps/categories-range.toml
# --out OUT_DIR --emit slurm`, then the `python3` line below on the finished output.
#
#   bash scripts/categories-range.sh BIN OUT_DIR
set -euo pipefail
bin=$1 out=$2
cd "$(dirname "$0")/.."
sweep=sweeps/categories-range.toml
"$bin" sweep "$sweep" --out "$out" --workers "${WORKERS:-2}" --no-report
python3 scripts/timing-study-lines.py categories "$sweep" "$out" > "$out/lines.txt"
echo "wrote $out/lines.txt"
