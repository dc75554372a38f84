#!/usr/bin/env bash
# The timing models on reproduction priors that no test or doc uses, as a sweep (issue #45's
# criterion; the study is sweeps/timing-reproduction-heldout-priors.toml): runs the sweep,
# then writes its lines into OUT_DIR/heldout-priors.txt. Resumable: finished jobs are skipped.
#
#   bash scripts/reproduction-heldout-priors.sh BIN OUT_DIR
#
# For a cluster: `BIN sweep sweeps/timing-reproduction-heldout-priors.toml --out OUT_DIR
# --emit slurm`, then this script on the finished output.
set -euo pipefail
bin=$1 out=$2
cd "$(dirname "$0")/.."
sweep=sweeps/timing-reproduction-heldout-priors.toml
"$bin" sweep "$sweep" --out "$out" --workers "${WORKERS:-2}" --no-report
python3 scripts/timing-study-lines.py reproduction-heldout "$sweep" "$out" > "$out/heldout-priors.txt"
echo "wrote $out/heldout-priors.txt"
