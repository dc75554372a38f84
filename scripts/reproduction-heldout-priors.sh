#!/usr/bin/env bash
# The timing models on reproduction priors that no test or doc uses (issue #45's criterion:
# mean tp/ts within 0.8-1.2 at every ts of a held-out prior): every timing model, seeds
# 1-4, on the intermediate prior alone (`inter`) and on priors 10-16 with 15-21 (`custom`),
# run defaults. One line per run: set-up, run, evaluation success, then per
# prior its slope and the mean tp/ts at each ts in order. Resumable: a run with a line is
# skipped.
#
#   bash scripts/reproduction-heldout-priors.sh BIN OUT_DIR   (lines in OUT_DIR/heldout-priors.txt)
set -uo pipefail
bin=$1 out=$2
mkdir -p "$out/runs"
touch "$out/heldout-priors.txt"
for setup in inter custom; do
  case $setup in
    inter) priors=intermediate ;;
    custom) priors=10-16,15-21 ;;
  esac
  for m in timecells-csc timecells-ms timecells-laplace ddm sbf; do
    for s in 1 2 3 4; do
      name="r-$setup-$m-$s"
      grep -q " $name " "$out/heldout-priors.txt" && continue
      d="$out/runs/$name"
      rm -rf "$d" "$d-eval"
      "$bin" train --model "$m" --task Reproduction-v0 --set "env.priors=$priors" --seed "$s" \
        --out "$d" > /dev/null 2>&1 || { echo "train failed: $name" >&2; continue; }
      "$bin" eval --run "$d" --out "$d-eval" > /dev/null 2>&1 || { echo "eval failed: $name" >&2; continue; }
      python3 - "$d-eval" "$setup" "$name" >> "$out/heldout-priors.txt" <<'PY'
import json, sys
m = json.load(open(sys.argv[1] + "/metrics.json"))
out = []
for c in m["reproduction"]["contexts"]:
    r = [round(x[1], 2) for x in c["ratio"]]
    out.append(f"  prior {c['prior']} slope {c['slope']:.2f} {r}")
print(sys.argv[2], sys.argv[3], f"succ {m['success_rate']:.2f}", " ".join(out), flush=True)
PY
    done
  done
done
