#!/usr/bin/env bash
# The project's test command: the Rust suite, then the Python package built into a local
# virtual environment (.venv) and its pytest suite. Needs only cargo and python3 (>= 3.9
# with venv); every dependency comes from crates.io and PyPI.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo test --release --workspace --locked
# `--workspace`: the features `cargo test --workspace` resolved, so nothing is rebuilt.
cargo build --release --locked --workspace --bins
python=${PYTHON:-python3}
if [[ ! -x .venv/bin/python ]]; then
    "$python" -m venv .venv || {
        # Interpreters without the venv module: virtualenv from PyPI.
        "$python" -m pip install --user --quiet virtualenv && "$python" -m virtualenv .venv
    }
fi
.venv/bin/python -m pip install --quiet --upgrade pip
.venv/bin/python -m pip install --quiet -r python/requirements-test.txt
# Builds the wheel (release, abi3, stripped extension) with maturin and installs it.
rm -rf target/wheel && .venv/bin/python -m pip wheel --quiet --no-deps ./python -w target/wheel
wheel=$(ls target/wheel/chronocooked-*.whl)
.venv/bin/python -m pip install --quiet --no-deps --force-reinstall "$wheel"
.venv/bin/python -m pip install --quiet "$wheel"
# pytest's tmp_path folders: outside the repository (some tests check that the package
# works there), in one temporary folder removed when the script exits.
pytest_tmp=$(mktemp -d)
trap 'rm -rf "$pytest_tmp"' EXIT
CHRONOCOOKED_BIN="$PWD/target/release/chronocooked" CHRONOCOOKED_WHEEL="$PWD/$wheel" \
    .venv/bin/python -m pytest -q -p no:cacheprovider --basetemp="$pytest_tmp/pytest" python/tests
