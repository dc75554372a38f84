#!/usr/bin/env bash
# Re-evaluates the kept curriculum-level policies of every finished multi-timer job under a
# sweep output folder with BIN's evaluation, replacing only each job's `eval/levels.csv`
# (e.g. after session 20 added the untrained TDs 1 … longest + 1 to each level's test).
# The job's own evaluation seed (its training seed) is used, so the rows of the trained TDs
# are unchanged; a job whose old rows are not all in the new file is reported and left as
# it was. Run `chronocooked paper collect` afterwards.
#
#   scripts/reeval-levels.sh BIN OUT_DIR
set -uo pipefail
bin=$1 out=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
n=0 bad=0
while read -r levels; do
    job=$(dirname "$(dirname "$levels")")
    [[ -f $job/eval/metrics.json && -d $job/run/levels ]] || continue
    rm -rf "$tmp/eval"
    if ! "$bin" eval --run "$job/run" --out "$tmp/eval" > "$tmp/log" 2>&1; then
        echo "FAILED $job: $(tail -1 "$tmp/log")"; bad=$((bad + 1)); continue
    fi
    if [[ -n $(grep -vxF -f "$tmp/eval/levels.csv" "$levels") ]]; then
        echo "CHANGED $job: its trained-TD rows differ; left as it was"; bad=$((bad + 1)); continue
    fi
    cp "$tmp/eval/levels.csv" "$levels.tmp" && mv "$levels.tmp" "$levels"
    n=$((n + 1))
done < <(find "$out" -path '*/eval/levels.csv')
echo "$n jobs re-evaluated, $bad left as they were"
[[ $bad -eq 0 ]]
