#!/usr/bin/env bash
# LSTM125 (PPO, the task's fast preset with its tolerance curriculum) on reproduction priors
# that no test uses: priors 10-16 with 15-21, seeds 1-4 (issue #45's criterion: mean tp/ts
# within 0.8-1.2 at every ts of a held-out prior). One line per run: run, evaluation
# success, then per prior its slope and the mean tp/ts at each ts in order. Resumable: a run
# with a line is skipped; two runs at a time.
#
#   bash scripts/reproduction-ppo-heldout.sh BIN OUT_DIR   (lines in OUT_DIR/lines.txt)
set -uo pipefail
bin=$(realpath "$1") out=$2
mkdir -p "$out/runs"
touch "$out/lines.txt"
one() {
  local bin=$1 out=$2 s=$3 name="lstm125-p10-16_15-21-s$3"
  grep -q "^$name " "$out/lines.txt" && return
  local d="$out/runs/$name"
  rm -rf "$d" "$d-eval"
  "$bin" train --model lstm125 --task Reproduction-v0 --preset fast --set env.priors=10-16,15-21 \
    --seed "$s" --out "$d" > "$d.log" 2>&1 || { echo "train failed: $name" >&2; return; }
  "$bin" eval --run "$d" --out "$d-eval" >> "$d.log" 2>&1 || { echo "eval failed: $name" >&2; return; }
  python3 - "$d-eval" "$name" >> "$out/lines.txt" <<'PY'
import json, sys
m = json.load(open(sys.argv[1] + "/metrics.json"))
out = []
for c in m["reproduction"]["contexts"]:
    r = [round(x[1], 2) for x in c["ratio"]]
    out.append(f"  prior {c['prior']} slope {c['slope']:.2f} {r}")
print(sys.argv[2], f"succ {m['success_rate']:.2f}", " ".join(out), flush=True)
PY
}
export -f one
printf "1\n2\n3\n4\n" | xargs -P 2 -I{} bash -c 'one "$0" "$1" {}' "$bin" "$out"
cat "$out/lines.txt"
