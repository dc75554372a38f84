"""Every Python block of the README and the guide (docs/, docs/tutorials/) runs as written.

Each block runs in a fresh folder holding links to the repository's folders it reads
(`examples/` for the example agents, `results/` for the leaderboard's committed baselines,
`zoo/`, `sweeps/`): as from the repository's root, with the installed package.
A block that imports sb3_contrib runs only where it is installed (as `test_sb3.py`'s tests
do). The shell blocks are run by the Rust suite (tests/doc_commands.rs).
"""
import os
import re
import subprocess
import sys

import pytest

from conftest import ROOT

FENCE = re.compile(r"^(?P<indent>[ \t]*)```python[ \t]*\n(?P<body>.*?)^(?P=indent)```", re.S | re.M)


def pages():
    found = [ROOT / "README.md"]
    for folder in ("docs", "docs/tutorials"):
        found += sorted((ROOT / folder).glob("*.md"))
    return found


def python_blocks():
    """(page:line, code) of every fenced Python block, its indentation removed."""
    out = []
    for page in pages():
        text = page.read_text()
        for m in FENCE.finditer(text):
            indent = len(m.group("indent"))
            code = "".join(line[indent:] if line.strip() else line
                           for line in m.group("body").splitlines(keepends=True))
            line = text[: m.start()].count("\n") + 1
            out.append((f"{page.relative_to(ROOT)}:{line}", code))
    return out


BLOCKS = python_blocks()


def test_the_guide_has_python_blocks_and_the_reader_finds_indented_ones():
    assert len(BLOCKS) >= 5, [b[0] for b in BLOCKS]
    m = FENCE.search("* item\n\n  ```python\n  x = 1\n  ```\n")
    assert m and m.group("body") == "  x = 1\n"


@pytest.mark.parametrize("where,code", BLOCKS, ids=[b[0] for b in BLOCKS])
def test_every_documented_python_block_runs(tmp_path, where, code):
    if "sb3_contrib" in code:
        pytest.importorskip("sb3_contrib")
    for folder in ("examples", "results", "zoo", "sweeps"):
        (tmp_path / folder).symlink_to(ROOT / folder)
    env = dict(os.environ, CHRONOCOOKED_CACHE=str(tmp_path / "cache"), MPLBACKEND="Agg")
    out = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, env=env,
                         capture_output=True, text=True, timeout=900)
    assert out.returncode == 0, f"{where}:\n{out.stderr[-4000:]}"
