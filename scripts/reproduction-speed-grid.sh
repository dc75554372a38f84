#!/usr/bin/env bash
# Timing by speed in the timing models' recorded activity on the reproduction task: each
# model trained with default settings on Reproduction-v0 (seeds 1-4), recorded with
# `record --summary --repeats 2 --seed SEED` (every ts of each prior, each start cell, twice),
# and the
# summaries' `production_speed` (KiNeT after Set, per prior) kept as one JSON line per run.
# Finished runs are skipped.
#
#   bash scripts/reproduction-speed-grid.sh BIN DIR
#   python3 scripts/reproduction-speed-table.py DIR/lines.jsonl
set -uo pipefail
bin=$1 dir=$2
mkdir -p "$dir"
for model in ddm sbf timecells-csc timecells-ms timecells-laplace; do
    for seed in 1 2 3 4; do
        run=$dir/$model-s$seed
        if [[ ! -f $run/agent.json ]]; then
            rm -rf "$run"
            "$bin" train --task Reproduction-v0 --model "$model" --seed "$seed" --out "$run" --quiet \
                > /dev/null 2>&1 || { echo "train failed: $run"; continue; }
        fi
        # The recording's noise is seeded with the run's seed (the default seed 0 would give
        # every run the same noise).
        if [[ ! -f $run/act.summary.json ]]; then
            "$bin" record --run "$run" --summary --repeats 2 --seed "$seed" --out "$run/act.json" \
                > /dev/null 2>&1 || { echo "record failed: $run"; continue; }
            rm -f "$run/act.json"
        fi
    done
done
python3 - "$dir" <<'PY'
import json, os, sys
root = sys.argv[1]
with open(os.path.join(root, "lines.jsonl"), "w") as out:
    for name in sorted(os.listdir(root)):
        path = os.path.join(root, name, "act.summary.json")
        if not os.path.isfile(path):
            continue
        model, seed = name.rsplit("-s", 1)
        for p in json.load(open(path)):
            for c in p.get("production_speed", []):
                out.write(json.dumps({"model": model, "seed": int(seed), "population": p["population"], **c}) + "\n")
PY
