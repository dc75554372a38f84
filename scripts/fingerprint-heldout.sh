#!/usr/bin/env bash
# Held-out seeds of every timing mechanism through `chronocooked fingerprint`: trains the
# jobs of `sweeps/mechanisms-heldout.toml` (seeds 40-47, never used by the committed
# study), then fingerprints each model x seed from its three runs (fixed interval TD 6 and
# TD 12, bisection 4-12) against the committed mechanisms. One line per agent: model, seed,
# nearest mechanism, distance, that mechanism's limit, verdict, nearest other mechanism, in
# the unit view and in the dynamics view.
# Committed lines: results/mechanisms-reference/heldout-fingerprints.txt.
# Resumable: finished sweep jobs and agents with a fingerprint.json are skipped.
#
#   bash scripts/fingerprint-heldout.sh BIN OUT_DIR   (lines in OUT_DIR/heldout.txt)
set -euo pipefail
bin=$1 out=$2
mkdir -p "$out"
"$bin" sweep sweeps/mechanisms-heldout.toml --out "$out/sweep" --workers 2 --no-report > /dev/null
: > "$out/heldout.txt"
for m in ddm sbf timecells-csc timecells-ms timecells-laplace; do
  for s in 40 41 42 43 44 45 46 47; do
    fp="$out/fingerprints/$m-$s"
    if [[ ! -f "$fp/fingerprint.json" ]]; then
      rm -rf "$fp"
      "$bin" fingerprint --run "$out/sweep/FixedInterval-v0/$m~env.td-6_stop_at_success-none/seed$s/run" \
        --run "$out/sweep/FixedInterval-v0/$m~env.td-12_stop_at_success-none/seed$s/run" \
        --run "$out/sweep/Bisection-v0/$m~env.short-4_env.long-12/seed$s/run" \
        --resamples 200 --out "$fp" > /dev/null
    fi
    python3 - "$fp/fingerprint.json" "$m" "$s" >> "$out/heldout.txt" <<'PY'
import json, sys
fp = json.load(open(sys.argv[1]))
parts = []
for view in ("units", "dynamics"):
    p = fp[view]
    d = sorted(p["distances"], key=lambda x: x["distance"])
    own = next(x for x in d if x["mechanism"] == p["nearest"])
    other = next(x for x in d if x["mechanism"] != p["nearest"])
    verdict = "identified" if p["identified"] else "not-identified"
    parts.append(f"{view}: nearest {p['nearest']} {own['distance']:.2f} (limit {own['limit']:.2f}) "
                 f"{verdict}; nearest other {other['mechanism']} {other['distance']:.2f}")
print(f"{sys.argv[2]} seed {sys.argv[3]}: " + " | ".join(parts))
PY
  done
done
cat "$out/heldout.txt"
