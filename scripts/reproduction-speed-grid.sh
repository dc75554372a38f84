#!/usr/bin/env bash
# Timing by speed in the timing models' recorded activity on the reproduction task, as a
# sweep (the study is sweeps/reproduction-speed.toml): runs the sweep, then writes the
# summaries' `production_speed` (KiNeT after Set) as one JSON line per run, population and
# prior into DIR/lines.jsonl. Resumable: finished jobs are skipped. On a cluster:
# `chronocooked sweep sweeps/reproduction-speed.toml --out DIR --emit slurm`, then the
# `python3` line below on the finished output.
#
#   bash scripts/reproduction-speed-grid.sh BIN DIR
#   python3 scripts/reproduction-speed-table.py DIR/lines.jsonl
set -euo pipefail
bin=$1 dir=$2
cd "$(dirname "$0")/.."
sweep=sweeps/reproduction-speed.toml
"$bin" sweep "$sweep" --out "$dir" --workers "${WORKERS:-2}" --no-report
python3 scripts/timing-study-lines.py reproduction-speed "$sweep" "$dir" > "$dir/lines.jsonl"
echo "wrote $dir/lines.jsonl"
