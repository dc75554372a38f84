#!/usr/bin/env bash
# Wall time of timing-model training with two builds of the CLI, alternating in one sitting:
# Reproduction-v0 (priors 9-15, the time cells' conjunctive code), 4,000 episodes, seed 3,
# R rounds. Prints `round model build seconds`; BENCHMARKS.md ("Timing-model training")
# takes the median per model and build.
#
#   bash scripts/bench-timing-compare.sh OLD_BIN NEW_BIN [R]
set -uo pipefail
old=$1 new=$2 R=${3:-3} out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for r in $(seq 1 $R); do
  for m in timecells-csc timecells-ms timecells-laplace ddm sbf; do
    for b in old new; do
      bin=$old; [[ $b == new ]] && bin=$new
      s=$(date +%s.%N)
      "$bin" train --task Reproduction-v0 --model $m --seed 3 --quiet --set env.priors=9-15 --set episodes=4000 --out "$out/$b-$m-$r" > /dev/null 2>&1
      e=$(date +%s.%N)
      echo "$r $m $b $(awk -v s="$s" -v e="$e" 'BEGIN { printf "%.3f", e - s }')"
    done
  done
done
