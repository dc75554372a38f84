#!/usr/bin/env bash
# The timing models on multi-oven bisection (issue #44 item 4): every model × oven set-up
# (2 and 3 ovens, synchronous and asynchronous; S 4, L 12) × seeds 1–4, default settings
# (`train`, then the evaluation protocol: TD 1 … L + 4 on every oven and on one oven alone),
# one line per run: success, then per oven its accuracy, BP, WF and the interference against
# the one-oven curve (ΔWF, ΔBP). Resumable: a run whose line exists is skipped.
#
#   bash scripts/multi-oven-timing-grid.sh BIN OUT_DIR
#   (lines in OUT_DIR/lines.txt; runs in OUT_DIR/runs/; table:
#   python3 scripts/multi-oven-timing-table.py OUT_DIR/lines.txt)
set -uo pipefail
bin=$1 out=$2
mkdir -p "$out/runs"
touch "$out/lines.txt"
for setup in ovens=2,asynchronous=false ovens=2,asynchronous=true ovens=3,asynchronous=false ovens=3,asynchronous=true; do
  for m in ddm sbf timecells-csc timecells-ms timecells-laplace; do
    for s in 1 2 3 4; do
      grep -q "^$setup $m $s " "$out/lines.txt" && continue
      d="$out/runs/$setup-$m-$s"
      rm -rf "$d" "$d-eval"
      sets=()
      for kv in ${setup//,/ }; do sets+=(--set "env.$kv"); done
      "$bin" train --model "$m" --task MultiOven-v0 "${sets[@]}" --seed "$s" \
        --out "$d" > /dev/null 2>&1 || { echo "train failed: $setup $m $s" >&2; continue; }
      "$bin" eval --run "$d" --out "$d-eval" > /dev/null 2>&1 || { echo "eval failed: $setup $m $s" >&2; continue; }
      python3 - "$d-eval" "$setup" "$m" "$s" >> "$out/lines.txt" <<'PY'
import json, sys
all_m = json.load(open(sys.argv[1] + "/metrics.json"))
m = all_m["multi_oven"]
fmt = lambda v, p=2: "na" if v is None else f"{v:.{p}f}"
single = m["single"]
sf = single.get("fit") if isinstance(single, dict) else None
out = [f"single acc {fmt(single.get('accuracy'))} bp {fmt(sf and sf['bp'])} wf {fmt(sf and sf['wf'])}"]
inter = {i["oven"]: i for i in m["interference"]}
for o in m["per_oven"]:
    f = o.get("fit")
    i = inter.get(o["oven"], {})
    out.append(f"oven{o['oven'] + 1} acc {fmt(o['accuracy'])} bp {fmt(f and f['bp'])} wf {fmt(f and f['wf'])}"
               f" dwf {fmt(i.get('d_wf'), 3)} dbp {fmt(i.get('d_bp'))}")
print(sys.argv[2], sys.argv[3], sys.argv[4], f"success {all_m['success_rate']:.3f}", " | ".join(out), flush=True)
PY
    done
  done
done
