"""The published package stays small: the wheel that scripts/test.sh builds (release
profile without debug info, extension stripped by maturin) is at most 10 MB."""

import os
from pathlib import Path

import pytest

LIMIT = 10_000_000  # bytes


def test_the_wheel_is_at_most_10_mb():
    # scripts/test.sh builds the wheel it installs and names it here.
    wheel = os.environ.get("CHRONOCOOKED_WHEEL")
    if not wheel:
        pytest.skip("no CHRONOCOOKED_WHEEL (the wheel is built by scripts/test.sh)")
    size = Path(wheel).stat().st_size
    assert size <= LIMIT, f"{wheel}: {size} bytes"
