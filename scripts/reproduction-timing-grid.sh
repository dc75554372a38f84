#!/usr/bin/env bash
# The timing models on the reproduction task, as sweeps (issue #45 item 3; the study is
# sweeps/timing-reproduction.toml and sweeps/timing-reproduction-ddm-memory.toml, run into one
# output folder): runs both, then writes the study's lines and table into OUT_DIR.
# Resumable: finished jobs are skipped.
#
#   bash scripts/reproduction-timing-grid.sh BIN OUT_DIR
#
# For a cluster: `BIN sweep FILE --out OUT_DIR --emit slurm` for each file, then this script on
# the finished output (the sweeps skip every finished job).
set -euo pipefail
bin=$1 out=$2
cd "$(dirname "$0")/.."
for sweep in sweeps/timing-reproduction.toml sweeps/timing-reproduction-ddm-memory.toml; do
  "$bin" sweep "$sweep" --out "$out" --workers "${WORKERS:-2}" --no-report
done
python3 scripts/timing-study-lines.py reproduction sweeps/timing-reproduction.toml "$out" > "$out/lines.txt"
python3 scripts/reproduction-timing-table.py "$out/lines.txt" > "$out/table.md"
echo "wrote $out/lines.txt, $out/table.md"
