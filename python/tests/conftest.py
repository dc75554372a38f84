"""Shared fixtures: the CLI binary (built by the project's test script) and paths."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(Path(__file__).resolve().parent))


def cli_path() -> Path:
    """The `chronocooked` CLI: $CHRONOCOOKED_BIN, else target/release/chronocooked."""
    env = os.environ.get("CHRONOCOOKED_BIN")
    path = Path(env) if env else ROOT / "target" / "release" / "chronocooked"
    return path


@pytest.fixture(scope="session")
def cli():
    path = cli_path()
    if not path.is_file():
        if shutil.which("cargo") is None:
            pytest.fail(f"{path} missing and no cargo to build it (run scripts/test.sh)")
        subprocess.run(["cargo", "build", "--release", "--locked", "--bin", "chronocooked"],
                       cwd=ROOT, check=True)
    return str(path)


@pytest.fixture(scope="session")
def golden_cases():
    import json

    with open(ROOT / "env" / "tests" / "golden" / "reference_traces.jsonl") as f:
        return [json.loads(line) for line in f if line.strip()]


@pytest.fixture(scope="session")
def extension_cases():
    """Golden traces of the reference's multi-anchor and multi-oven classes."""
    import json

    with open(ROOT / "env" / "tests" / "golden" / "extension_traces.jsonl") as f:
        return [json.loads(line) for line in f if line.strip()]


def pytest_configure(config):
    config.addinivalue_line(
        "markers", "sb3: needs stable-baselines3 and sb3-contrib (skipped where absent)")
