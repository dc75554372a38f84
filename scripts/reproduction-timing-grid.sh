#!/usr/bin/env bash
# The timing models on the reproduction task (issue #45 item 3): every model × set-up ×
# seeds 1–4, default settings (`train`, then the evaluation protocol: every ts of every
# prior × gain), one line per run: success, then per context (prior, gain) the regression
# slope of tp on ts, BIAS, sqrt(VAR), the Weber fraction of tp, the range of mean tp/(g ts)
# over the prior's ts, and the best observer model with its fitted wm and wp.
# Set-ups: the default task (short and long priors, cued); gains 1 and 1.5 (Remington et
# al. 2018); drift-diffusion with memory averaging (reproduction_rate 0.5).
# Resumable: a run whose line exists is skipped; a trained run without a line is only
# evaluated again (delete its folder to retrain).
#
#   bash scripts/reproduction-timing-grid.sh BIN OUT_DIR
#   (lines in OUT_DIR/lines.txt; runs in OUT_DIR/runs/)
set -uo pipefail
bin=$1 out=$2
mkdir -p "$out/runs"
touch "$out/lines.txt"
run() { # setup model seed [--set k=v]...
  local setup=$1 m=$2 s=$3; shift 3
  grep -q "^$setup $m $s " "$out/lines.txt" && return
  local d="$out/runs/$setup-$m-$s"
  rm -rf "$d-eval"
  if [ ! -f "$d/summary.json" ]; then
    rm -rf "$d"
    "$bin" train --model "$m" --task Reproduction-v0 "$@" --seed "$s" --out "$d" > /dev/null 2>&1 \
      || { echo "train failed: $setup $m $s" >&2; return; }
  fi
  "$bin" eval --run "$d" --out "$d-eval" > /dev/null 2>&1 || { echo "eval failed: $setup $m $s" >&2; return; }
  python3 - "$d-eval" "$setup" "$m" "$s" >> "$out/lines.txt" <<'PY'
import json, sys
m = json.load(open(sys.argv[1] + "/metrics.json"))
fmt = lambda v: "na" if v is None else f"{v:.2f}"
out = []
for c in m["reproduction"]["contexts"]:
    r = [x[1] for x in c["ratio"]]
    o = c.get("observer") or {"best": "na", "wm": None, "wp": None}  # fitted at gain 1 only
    rng = f"{min(r):.2f}-{max(r):.2f}" if r else "na"
    out.append(f"prior{c['prior']} g{c['gain']:g} slope {fmt(c['slope'])} bias {fmt(c['bias'])}"
               f" sqrtvar {fmt(c['sqrt_var'])} wf {fmt(c['weber'])} ratio {rng}"
               f" best {o['best']} wm {fmt(o['wm'])} wp {fmt(o['wp'])}")
print(sys.argv[2], sys.argv[3], sys.argv[4], f"success {m['success_rate']:.3f}", " | ".join(out), flush=True)
PY
}
for m in ddm sbf timecells-csc timecells-ms timecells-laplace; do
  for s in 1 2 3 4; do run default "$m" "$s"; done
done
for s in 1 2 3 4; do run ddm-rate0.5 ddm "$s" --set reproduction_rate=0.5; done
for m in ddm sbf timecells-csc timecells-ms timecells-laplace; do
  for s in 1 2 3 4; do run gains "$m" "$s" --set env.gains=1,1.5; done
done
