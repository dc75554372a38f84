#!/usr/bin/env bash
# Prints results/baselines/README.md's "Committed baselines on the leaderboard" table from the committed
# results/paper-core jobs, as `chronocooked report --baselines` computes it (tests/baselines.rs
# checks that README against the job files, so rerun this after collecting repeats):
#
#   bash scripts/baseline-table.sh [BIN]
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-target/release/chronocooked}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$bin" eval --agent oracle --env td=12 --out "$tmp/eval" > /dev/null
"$bin" report --eval "$tmp/eval" --baselines --out "$tmp/report" > /dev/null
python3 - "$tmp/report/report.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
def pm(r, key):
    return f"{float(r[key]):.3f} ± {float(r[key + '_sd']):.3f}"
print("| model | runs | FI success | anchor accuracy | FOC / TD |")
print("|---|---:|---:|---:|---:|")
for model in ["cnn-mlp", "lstm125", "ctrnn125", "ctrnn-reservoir125"]:
    r = next(r for r in rows if r["model"] == f"{model} (paper-core)")
    print(f"| {model} | {r['runs']} | {pm(r, 'fi_success')} | {pm(r, 'bisection_accuracy')} | {pm(r, 'foc_over_td')} |")
PY
