#!/usr/bin/env python3
"""Rewrites the `AGENTS` list of training/src/agent_zoo/embedded.rs from zoo/index.json
(run after `chronocooked zoo add`; a test checks that the two agree)."""
import json
import pathlib
import re

root = pathlib.Path(__file__).resolve().parents[1]
agents = json.loads((root / "zoo" / "index.json").read_text())["agents"]
path = root / "training" / "src" / "agent_zoo" / "embedded.rs"
src = path.read_text()
body = "".join(f'    zoo_agent!("{a}"),\n' for a in agents)
new = "pub static AGENTS: &[(&str, AgentFiles)] = &[\n" + body + "];"
src, n = re.subn(r"pub static AGENTS: &\[\(&str, AgentFiles\)\] = &\[[^\]]*\];", new, src)
assert n == 1, "AGENTS list not found"
path.write_text(src)
print(f"{len(agents)} agents in {path.relative_to(root)}")
