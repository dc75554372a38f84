#!/usr/bin/env bash
# Python baseline vs chronocooked, training env-steps/s, in one run on one machine.
#
#   bash bench/run_baseline.sh [PYTHON] [CHRONOCOOKED] [REF_DIR]
#
# Arguments (or environment variables) with defaults:
#   PYTHON        .venv-sb3/bin/python   venv with bench/requirements-sb3.txt
#   CHRONOCOOKED  ./target/release/chronocooked
#   REF_DIR       ref (relative to the repo root) folder holding the original time_production_basic.py
#   PPO_UPDATES   5   timed SB3 PPO updates (1000 env steps each, after 1 warm-up update)
#   RPPO_UPDATES  3   timed sb3-contrib RecurrentPPO updates per LSTM layout
#   RUST_UPDATES  4   updates measured by `chronocooked bench train`
#
# Runs from the repository root. Step 1: bench/sb3_baseline.py (SB3 PPO CNN-MLP and
# RecurrentPPO LSTM125, FI TD=12, one torch thread). Step 2: `chronocooked bench train`
# (cnn-mlp, lstm125, ctrnn125) on the native engine, then on burn autodiff. Load average is printed before, between and after.
set -euo pipefail
cd "$(dirname "$0")/.."

PYTHON="${1:-${PYTHON:-.venv-sb3/bin/python}}"
CHRONOCOOKED="${2:-${CHRONOCOOKED:-./target/release/chronocooked}}"
REF_DIR="${3:-${REF_DIR:-ref}}"
PPO_UPDATES="${PPO_UPDATES:-5}"
RPPO_UPDATES="${RPPO_UPDATES:-3}"
RUST_UPDATES="${RUST_UPDATES:-4}"

echo "== $(date -u '+%Y-%m-%dT%H:%M:%SZ') $(uname -srm), $(nproc) CPUs"
grep -m1 'model name' /proc/cpuinfo || true
echo "python: $PYTHON   chronocooked: $CHRONOCOOKED   ref: $REF_DIR"
echo "== uptime (before): $(uptime)"

echo "== SB3 baseline: $PYTHON bench/sb3_baseline.py --ref-dir $REF_DIR --ppo-updates $PPO_UPDATES --rppo-updates $RPPO_UPDATES"
"$PYTHON" -W ignore::UserWarning bench/sb3_baseline.py --ref-dir "$REF_DIR" \
    --ppo-updates "$PPO_UPDATES" --rppo-updates "$RPPO_UPDATES"

echo "== uptime (between): $(uptime)"

echo "== Rust (native engine, the default): $CHRONOCOOKED bench train --updates $RUST_UPDATES"
"$CHRONOCOOKED" bench train --updates "$RUST_UPDATES"

echo "== Rust (burn autodiff engine): $CHRONOCOOKED bench train --updates $RUST_UPDATES --set engine=burn"
"$CHRONOCOOKED" bench train --updates "$RUST_UPDATES" --set engine=burn

echo "== uptime (after): $(uptime)"
