#!/usr/bin/env bash
# Load test of the sweep runner (issue #65): JOBS tiny jobs (the random agent's evaluation on
# fixed interval, one per seed) on WORKERS workers, with a fault planted in FAULTS jobs chosen
# at random (seeded): a file where the job's `eval/` folder goes, so its evaluation fails with
# an error naming the path. It checks that every healthy job finishes, that the sweep names
# every failed one, and that a rerun (faults removed) runs exactly the failed ones. The sweep
# process's resident memory and open files are sampled every 0.2 s; the summary goes to
# OUT/load.txt.
#
#   bash scripts/load-test.sh target/release/chronocooked lab-out/load-test [JOBS] [WORKERS] [FAULTS] [SEED]
set -euo pipefail
BIN=$(realpath "$1")
OUT=$2
JOBS=${3:-500}
WORKERS=${4:-2}
FAULTS=${5:-25}
SEED=${6:-1}
rm -rf "$OUT"
mkdir -p "$OUT"
cd "$OUT"
{
    echo 'name = "load"'
    echo 'tasks = ["FixedInterval-v0"]'
    echo 'models = ["random"]'
    echo "seeds = [$(seq -s ', ' 1 "$JOBS")]"
    echo 'record = false'
    echo 'export = false'
    echo 'set = ["env.td=6"]'
} > load.toml
"$BIN" sweep load.toml --out out --dry-run | awk '$1 == "todo" {print $2}' > jobs.txt
test "$(wc -l < jobs.txt)" -eq "$JOBS"
# The faulted jobs: a seeded shuffle of the job list.
awk -v seed="$SEED" 'BEGIN {srand(seed)} {print rand() "\t" $0}' jobs.txt | sort -n | cut -f2 |
    head -n "$FAULTS" | sort > faulted.txt
while read -r id; do
    mkdir -p "out/$id"
    echo "planted fault" > "out/$id/eval"
done < faulted.txt

sample() { # PID FILE: RSS (kB) and open files of PID until it ends
    while kill -0 "$1" 2>/dev/null; do
        rss=$(awk '/^VmRSS/ {print $2}' "/proc/$1/status" 2>/dev/null || true)
        fds=$(ls "/proc/$1/fd" 2>/dev/null | wc -l || true)
        [ -n "$rss" ] && echo "$(date +%s.%N) $rss $fds" >> "$2"
        sleep 0.2
    done
}
start=$(date +%s.%N)
set +e
"$BIN" sweep load.toml --out out --workers "$WORKERS" --no-report > first.log 2>&1 &
pid=$!
sample "$pid" samples.txt &
wait "$pid"
rc=$?
set -e
wait
end=$(date +%s.%N)
done_jobs=$(find out -name progress.json -exec grep -l '"done": true' {} + | wc -l)
named=0
while read -r id; do grep -qF "$id" first.log && named=$((named + 1)); done < faulted.txt
# Rerun with the faults removed: exactly the failed jobs run.
while read -r id; do rm -f "out/$id/eval"; done < faulted.txt
"$BIN" sweep load.toml --out out --workers "$WORKERS" --no-report > rerun.log 2>&1
reran=$(grep -o 'running [0-9]* with' rerun.log | awk '{print $2}')
after=$(find out -name progress.json -exec grep -l '"done": true' {} + | wc -l)
awk -v jobs="$JOBS" -v faults="$FAULTS" -v rc="$rc" -v done_jobs="$done_jobs" -v named="$named" \
    -v reran="$reran" -v after="$after" -v secs="$(echo "$end - $start" | bc)" '
    NR == 1 {rss0 = $2; fd0 = $3}
    {n++; if ($2 > rssmax) rssmax = $2; if ($3 > fdmax) fdmax = $3
     if (n <= 25) {a += $2} ; last[n] = $2}
    END {
        for (i = n - 24; i <= n; i++) if (i > 0) b += last[i]
        printf "jobs %d, faulted %d, first run: exit %d, %d jobs done (healthy %d), %d of %d faulted jobs named in its output, %.1f s\n", jobs, faults, rc, done_jobs, jobs - faults, named, faults, secs
        printf "rerun without the faults: ran %s jobs, %d done in all\n", reran, after
        printf "sweep process: %d samples; RSS first %d kB, max %d kB, mean of first 25 samples %.0f kB, of last 25 %.0f kB; open files first %d, max %d\n", n, rss0, rssmax, a / (n < 25 ? n : 25), b / (n < 25 ? n : 25), fd0, fdmax
    }' samples.txt | tee load.txt
