#!/usr/bin/env bash
# No-regression check of a change's speed: runs `bench env` (FI, scalar and 256-env codes)
# and `bench train` (reference preset, CNN-MLP / LSTM125 / CTRNN125) with two builds of the
# CLI in one session, alternating old, new, old, new so drifting machine load hits both
# alike, and prints the mean of each measurement and the new/old ratio.
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
import collections, sys
v = collections.defaultdict(list)
for line in open(sys.argv[1]):
    side, what, rate = line.split()
    v[(what, side)].append(float(rate))
print(f"{'measurement':<14} {'old (mean)':>14} {'new (mean)':>14} {'new/old':>8}   runs   old min-max / new min-max")
for what in dict.fromkeys(w for w, _ in v):
    o, n = v[(what, "old")], v[(what, "new")]
    mo, mn = sum(o) / len(o), sum(n) / len(n)
    print(f"{what:<14} {mo:>14,.0f} {mn:>14,.0f} {mn / mo:>8.3f}   {len(o)}+{len(n)}"
          f"   {min(o):,.0f}-{max(o):,.0f} / {min(n):,.0f}-{max(n):,.0f}")
PY
rm -f "$log"
