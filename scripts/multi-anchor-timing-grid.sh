#!/usr/bin/env bash
# The timing models on multi-anchor categorization (issue #44 item 4): every model × anchor
# set × seeds 1–4, default settings (`train`, then the evaluation protocol's probes 1 … last
# anchor + 4 from every start cell), one line per run: anchor accuracy and each boundary's
# fit (BP [95% CI], the pair's GM and AM, WF). Resumable: a run whose line exists is skipped.
#
#   bash scripts/multi-anchor-timing-grid.sh BIN OUT_DIR
#   (lines in OUT_DIR/lines.txt; runs in OUT_DIR/runs/; table:
#   python3 scripts/multi-anchor-timing-table.py OUT_DIR/lines.txt)
#
# Other anchor sets or seeds: ANCHOR_SETS="5,9,16,28 4,7,12" SEEDS="1 2 3 4 5 6 7 8" bash …
set -uo pipefail
bin=$1 out=$2
mkdir -p "$out/runs"
touch "$out/lines.txt"
for set in ${ANCHOR_SETS:-4,8,16 5,9,16 4,8,14,24 3,10,20,25 4,12,18,25}; do
  for m in ddm sbf timecells-csc timecells-ms timecells-laplace; do
    for s in ${SEEDS:-1 2 3 4}; do
      grep -q "^$set $m $s " "$out/lines.txt" && continue
      d="$out/runs/$set-$m-$s"
      rm -rf "$d" "$d-eval"
      "$bin" train --model "$m" --task MultiAnchor-v0 --set "env.anchors=$set" --seed "$s" \
        --out "$d" > /dev/null 2>&1 || { echo "train failed: $set $m $s" >&2; continue; }
      "$bin" eval --run "$d" --out "$d-eval" > /dev/null 2>&1 || { echo "eval failed: $set $m $s" >&2; continue; }
      python3 - "$d-eval" "$set" "$m" "$s" >> "$out/lines.txt" <<'PY'
import json, sys
m = json.load(open(sys.argv[1] + "/metrics.json"))["multi_anchor"]
out = []
for b in m["boundaries"]:
    f = b["fit"]
    if f is None or f.get("bp_ci") is None:
        out.append("nofit")
        continue
    lo, hi = f["bp_ci"]
    g, a = b["gm"], b["am"]
    out.append(f"{f['bp']:.2f}[{lo:.2f},{hi:.2f}]gm{g:.2f}{'*' if lo <= g <= hi else ' '}"
               f"am{a:.1f}{'*' if lo <= a <= hi else ' '}wf{f['wf']:.2f}")
print(sys.argv[2], sys.argv[3], sys.argv[4], f"acc {m['anchor_accuracy']:.3f}", " | ".join(out))
PY
    done
  done
done
