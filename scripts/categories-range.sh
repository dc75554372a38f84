#!/usr/bin/env bash
# Unit categories of the timing models at every FI TD of the paper, with default settings:
# `train` then `record --probe --summary` (one repeat), for each model x TD x seed. Prints one
# line per population and TD: model seed TD population units and the category counts.
#
#   bash scripts/categories-range.sh target/release/chronocooked OUT_DIR [SEEDS] [MODELS]
#
# Defaults: seeds "23 31 37", models "sbf timecells-csc ddm" (the populations of issue #46).
set -euo pipefail
bin=$1
out=$2
seeds=${3:-23 31 37}
models=${4:-sbf timecells-csc ddm}
mkdir -p "$out"
for model in $models; do
    for seed in $seeds; do
        for td in 4 6 9 12 18 24; do
            run="$out/$model-seed$seed-td$td"
            [[ -f "$run.summary.json" ]] || {
                "$bin" train --task FixedInterval-v0 --model "$model" --seed "$seed" \
                    --set "env.td=$td" --out "$run" --quiet > /dev/null
                "$bin" record --run "$run" --probe --seed "$seed" --summary \
                    --out "$run.json" > /dev/null
            }
            python3 - "$run.summary.json" "$model" "$seed" "$td" <<'PY'
import json, sys
path, model, seed, td = sys.argv[1:]
for pop in json.load(open(path)):
    if pop["population"] in ("value", "rpe", "drift"):
        continue
    for t in pop["by_td"]:
        c = t["categories"]
        counts = " ".join(f"{k} {v}" for k, v in c["counts"].items() if v) if c else t["undefined"]
        print(f"{model} seed {seed} TD {td} {pop['population']}: {t['units']} units: {counts}")
PY
        done
    done
done
