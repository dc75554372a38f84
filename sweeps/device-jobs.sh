#!/usr/bin/env bash
# Runs a sweep's unfinished jobs on a lent many-core machine (the `device` tool's `run`) and
# leaves in $OUT what comes back: the finished jobs' compact results (done.tgz.*) and, for the
# jobs still running at the deadline, their run folders with only the newest checkpoint
# (partial.tgz.*), each split below the 16 MiB file limit. Here, unpack both into the local
# sweep folder (`cat done.tgz.* | tar xzf - -C lab-out/STUDY`, likewise partial) and resume
# with sweeps/run-jobs.sh; `paper collect` takes the finished ones.
#
# The binary travels gzipped in a folder that .git/info/exclude ignores (name it in `carry`):
#   gzip -c target/release/chronocooked > .devbin/cc.gz
#   run: bash sweeps/device-jobs.sh .devbin/cc.gz SWEEP_FILE ID_REGEX RESULTS_DIR SECONDS [WORKERS]
# A second call can continue the partial jobs: carry their tarball and unpack it into
# /tmp/o/sweep before calling this script.
set -u
gz=$1 file=$2 pattern=$3 results=$4 secs=$5 workers=${6:-$(nproc)}
mkdir -p /tmp/b /tmp/o && gunzip -c "$gz" > /tmp/b/cc && chmod +x /tmp/b/cc
bash sweeps/run-jobs.sh /tmp/b/cc "$file" /tmp/o/sweep "$workers" "$secs" "$pattern" "$results"
split -b 15M /tmp/o/sweep.tgz "$OUT/done.tgz."
cd /tmp/o/sweep || exit 1
for j in $(find . -name job.json -printf '%h\n'); do
    [ -f "$j/eval/metrics.json" ] || echo "$j"
done > /tmp/partial
echo "unfinished: $(wc -l < /tmp/partial)"
while read -r j; do
    find "$j" -type f ! -path '*/checkpoints/step-*' ! -path '*/figures/*'
    find "$j/run/checkpoints" -name 'step-*.json' 2> /dev/null | sort | tail -1
done < /tmp/partial > /tmp/list
tar czf - -T /tmp/list | split -b 15M - "$OUT/partial.tgz."
ls -la "$OUT"
