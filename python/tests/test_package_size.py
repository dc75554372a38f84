"""The published package stays small: the compiled extension (stripped, no debug info) and
the wheel built by scripts/test.sh are at most 10 MB each."""

import os
from pathlib import Path

import chronocooked._core

LIMIT = 10_000_000  # bytes


def test_the_installed_extension_is_at_most_10_mb():
    size = Path(chronocooked._core.__file__).stat().st_size
    assert size <= LIMIT, f"{chronocooked._core.__file__}: {size} bytes"


def test_the_wheel_is_at_most_10_mb():
    # scripts/test.sh builds the wheel it installs and names it here.
    wheel = os.environ.get("CHRONOCOOKED_WHEEL")
    if not wheel:
        import pytest

        pytest.skip("no CHRONOCOOKED_WHEEL (the wheel is built by scripts/test.sh)")
    size = Path(wheel).stat().st_size
    assert size <= LIMIT, f"{wheel}: {size} bytes"
