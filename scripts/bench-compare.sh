#!/usr/bin/env bash
# No-regression check of a change's speed: runs `bench env` (FI, scalar and 256-env codes)
# and `bench train` (reference preset, CNN-MLP / LSTM125 / CTRNN125) with two builds of the
# CLI in one session, alternating old, new, old, new so drifting machine load hits both
# alike, and prints each measurement's mean and range and three new/old ratios: of the
# means, of the best runs, and the median of the rounds' paired ratios.
#
#   bash scripts/bench-compare.sh OLD_BIN NEW_BIN [ROUNDS]
#   MODELS=lstm125,lstm256,ctrnn256 TRAIN_SETS="--set env.td=12" UPDATES=3 bash scripts/bench-compare.sh ...
#   (MODELS: the models of `bench train`, default its own; TRAIN_SETS: extra arguments)
#   e.g. git worktree add /tmp/old <commit> && (cd /tmp/old && cargo build --release)
#        bash scripts/bench-compare.sh /tmp/old/target/release/chronocooked target/release/chronocooked
set -euo pipefail
old=$1 new=$2 rounds=${3:-2}
log=$(mktemp)
trap 'rm -f "$log"' EXIT
for ((r = 1; r <= rounds; r++)); do
    for side in old new; do
        bin=${!side}
        "$bin" bench env --seconds 2 --json | python3 -c '
import json, sys
for l in sys.stdin:
    if l.startswith("{"):
        d = json.loads(l)
        if d["encoding"] == "codes":
            print(sys.argv[1], "env-" + d["mode"], d["steps_per_sec"])' "$side" >> "$log"
        # shellcheck disable=SC2086
        "$bin" bench train --updates "${UPDATES:-5}" ${MODELS:+--models "$MODELS"} ${TRAIN_SETS:-} 2> /dev/null \
            | awk -v s="$side" '$6 == "env-steps/s" {print s, $2, $5}' >> "$log"
    done
done
python3 - "$log" <<'PY'
import collections, statistics, sys
v = collections.defaultdict(list)
for line in open(sys.argv[1]):
    side, what, rate = line.split()
    v[(what, side)].append(float(rate))
# Three estimators of new/old, all reported: the ratio of means; the ratio of the best
# (fastest) measurement of each build, which interference can only lower (it adds time,
# never removes work; Chen & Revels 2016, "Robust benchmarking in noisy environments",
# arXiv:1608.04295); and the median of the rounds' paired ratios (new over the old run just
# before it, so slow drifts cancel).
print(f"{'measurement':<14} {'old (mean)':>12} {'new (mean)':>12} {'mean':>6} {'best':>6}"
      f" {'paired':>6}   runs   old min-max / new min-max")
for what in dict.fromkeys(w for w, _ in v):
    o, n = v[(what, "old")], v[(what, "new")]
    mo, mn = sum(o) / len(o), sum(n) / len(n)
    paired = statistics.median(b / a for a, b in zip(o, n))
    print(f"{what:<14} {mo:>12,.0f} {mn:>12,.0f} {mn / mo:>6.3f} {max(n) / max(o):>6.3f}"
          f" {paired:>6.3f}   {len(o)}+{len(n)}"
          f"   {min(o):,.0f}-{max(o):,.0f} / {min(n):,.0f}-{max(n):,.0f}")
PY
rm -f "$log"
