#!/usr/bin/env bash
# Held-out seeds of every timing mechanism through the fingerprint: trains the jobs of
# `sweeps/mechanisms-heldout.toml` (seeds 40-47, never used by the committed study), then
# `chronocooked fingerprint --sweep` fingerprints each model x seed from its three runs
# (fixed interval TD 6 and TD 12, bisection 4-12) against the committed mechanisms. One line
# per agent: model, seed, nearest mechanism, distance, that mechanism's limit, verdict,
# nearest other mechanism, in the unit view and in the dynamics view.
# Committed lines: results/mechanisms-reference/heldout-fingerprints.txt.
# Resumable: finished sweep jobs are skipped and finished agents placed again from their
# folders. On a cluster: `chronocooked sweep sweeps/mechanisms-heldout.toml --out OUT_DIR/sweep
# --emit slurm`, then the `fingerprint --sweep` line below on the finished output.
#
#   bash scripts/fingerprint-heldout.sh BIN OUT_DIR   (lines in OUT_DIR/heldout.txt)
set -euo pipefail
bin=$1 out=$2
cd "$(dirname "$0")/.."
"$bin" sweep sweeps/mechanisms-heldout.toml --out "$out/sweep" --workers "${WORKERS:-2}" --no-report > /dev/null
"$bin" fingerprint --sweep "$out/sweep" --out "$out/fingerprints" --resamples 200 > /dev/null
cp "$out/fingerprints/fingerprints.txt" "$out/heldout.txt"
cat "$out/heldout.txt"
