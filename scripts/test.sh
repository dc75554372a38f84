#!/usr/bin/env bash
# The project's test command: the Rust suite, then the Python package built into a local
# virtual environment (.venv) and its pytest suite. Needs only cargo and python3 (>= 3.9
# with venv); every dependency comes from crates.io and PyPI.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo test --release --workspace --locked
cargo build --release --locked --bin chronocooked
python=${PYTHON:-python3}
if [[ ! -x .venv/bin/python ]]; then
    "$python" -m venv .venv || {
        # Interpreters without the venv module: virtualenv from PyPI.
        "$python" -m pip install --user --quiet virtualenv && "$python" -m virtualenv .venv
    }
fi
.venv/bin/python -m pip install --quiet --upgrade pip
.venv/bin/python -m pip install --quiet -r python/requirements-test.txt
# Builds the extension (release, abi3) with maturin and installs it.
.venv/bin/python -m pip install --quiet ./python
CHRONOCOOKED_BIN="$PWD/target/release/chronocooked" .venv/bin/python -m pytest -q python/tests
