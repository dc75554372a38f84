#!/usr/bin/env bash
# Runs the unfinished jobs of a sweep whose ids match a pattern, WORKERS at a time, for at
# most SECONDS (for a many-core machine or a time-limited allocation), then packs the
# compact results of every job (configs, learning curves, evaluation metrics and episode
# records — no checkpoints) into OUT_DIR.tgz. Resumable: a rerun skips finished stages and
# PPO runs continue from their last checkpoint.
#
# Jobs whose compact results already sit in RESULTS_DIR/jobs/<id>/ (`chronocooked paper
# collect`) are skipped too, so a study resumes on a fresh machine from the repository.
#
#   sweeps/run-jobs.sh BIN SWEEP_FILE OUT_DIR WORKERS SECONDS [ID_REGEX] [RESULTS_DIR]
#   e.g. sweeps/run-jobs.sh target/release/chronocooked sweeps/paper-core.toml \
#            lab-out/paper-core 16 540 'lstm125' results/paper-core
set -uo pipefail
bin=$1 file=$2 out=$3 workers=$4 secs=$5 pattern=${6:-.} results=${7:-}
mkdir -p "$out"
tgz=$(realpath -m "$out.tgz")
"$bin" sweep "$file" --out "$out" --dry-run | awk '$1 == "todo" {print $2}' \
    | grep -E -- "$pattern" \
    | while read -r id; do
        [[ -n "$results" && -f "$results/jobs/$id/job.json" ]] || echo "$id"
    done > "$out.todo" || true
echo "$(wc -l < "$out.todo") jobs to run, $workers at a time, for at most $secs s"
setsid xargs -a "$out.todo" -P "$workers" -I{} \
    "$bin" sweep-job "$file" --out "$out" --id {} >> "$out.log" 2>&1 &
pid=$!
for ((t = 0; t < secs; t += 5)); do
    kill -0 "$pid" 2> /dev/null || break
    sleep 5
done
# Stop what is still running (its finished stages and checkpoints are kept).
kill -TERM -- "-$pid" 2> /dev/null
wait "$pid" 2> /dev/null
"$bin" sweep "$file" --out "$out" --dry-run | awk '{print $1}' | sort | uniq -c
(cd "$out" && find . \( -name job.json -o -name progress.json -o -path '*/run/config.json' \
    -o -path '*/run/curves.csv' -o -path '*/run/summary.json' -o -path '*/eval/metrics.json' \
    -o -path '*/eval/eval.json' -o -path '*/eval/records.jsonl' -o -path '*/eval/levels.csv' \) -print0 \
    | tar czf "$tgz" --null -T -)
ls -la "$tgz"
