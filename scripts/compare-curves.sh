#!/usr/bin/env bash
# Bit-identity check of a refactor: trains the same short runs (reference preset, a few
# updates) with two builds of the CLI and compares their learning curves byte for byte
# (every column but the wall-clock ones).
#
#   bash scripts/compare-curves.sh OLD_BIN NEW_BIN [OUT_DIR]
#   e.g. git worktree add /tmp/old <commit> && (cd /tmp/old && cargo build --release)
#        bash scripts/compare-curves.sh /tmp/old/target/release/chronocooked target/release/chronocooked
#
# Runs: CNN-MLP, LSTM125 and CTRNN125 on FI TD 6 (3000 env steps = 3 updates each), and the
# drift-diffusion timing model (its default training). Exit status 1 on any difference.
set -uo pipefail
old=$1 new=$2 out=${3:-$(mktemp -d)}
status=0
run() { # BIN LABEL MODEL STEPS...
    local bin=$1 label=$2 model=$3; shift 3
    "$bin" train --task FixedInterval-v0 --model "$model" --seed 3 --quiet \
        --set env.td=6 "$@" --out "$out/$label/$model" > /dev/null 2>&1
}
# The curves without their wall-clock columns (wall_s, steps_per_s, rollout_s, optimize_s).
timing_free() {
    python3 -c 'import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
drop = {"wall_s", "steps_per_s", "rollout_s", "optimize_s"}
keep = [i for i, h in enumerate(rows[0]) if h not in drop]
for r in rows:
    print(",".join(r[i] for i in keep))' "$1"
}
for model in ${MODELS:-cnn-mlp lstm125 ctrnn125 ddm}; do
    steps=()
    case $model in
        ddm | sbf* | timecells-*) ;;  # timing models: their default training
        *) steps=(--steps 3000) ;;    # PPO: a few updates of the reference preset
    esac
    run "$old" old "$model" "${steps[@]}"
    run "$new" new "$model" "${steps[@]}"
    a=$(ls "$out/old/$model"/curves.csv 2> /dev/null) b=$(ls "$out/new/$model"/curves.csv 2> /dev/null)
    if [[ -z $a || -z $b ]]; then
        echo "$model: no curves.csv (see $out)"; status=1
    elif cmp -s <(timing_free "$a") <(timing_free "$b"); then
        echo "$model: identical ($(($(wc -l < "$a") - 1)) curve rows)"
    else
        echo "$model: DIFFERENT"; diff <(timing_free "$a") <(timing_free "$b") | head -5; status=1
    fi
done
exit $status
