#!/usr/bin/env python3
"""Pastes results/mechanisms/mechanisms.md (written by `chronocooked mechanisms
results/mechanisms`) and the study's job count into results/mechanisms/README.md,
between the `<!-- mech -->` markers. Run from the repository root after collecting.

    python3 scripts/mechanisms-results.py
"""
import re, subprocess, pathlib
md = pathlib.Path('results/mechanisms/mechanisms.md').read_text()
tables = md.split('\n', 2)[2].replace('## Nearest mechanism', '**Nearest mechanism**')
done = len(list(pathlib.Path('results/mechanisms/jobs').glob('*/*/seed*')))
status = (f"**Status: {done} of 108 jobs finished** (every timing-mechanism job; the PPO agents' jobs are "
          "running — resume with `chronocooked sweep sweeps/mechanisms.toml --out lab-out/mechanisms "
          "--workers 2`, then `chronocooked paper collect lab-out/mechanisms --out results/mechanisms` and "
          "`chronocooked mechanisms results/mechanisms`). The agent rows below are preliminary: they rest on "
          "the PPO agents' jobs finished so far (n per model in the table; bisection features only where its jobs "
          "finished), so they are no finding yet.")
p = pathlib.Path('results/mechanisms/README.md'); s = p.read_text()
s = re.sub(r'(\*\*Status: \d+ of 108 jobs finished\*\*.*?no finding yet\.|MECH_STATUS)', status, s, count=1, flags=re.S)
s = re.sub(r'(<!-- mech -->.*?<!-- /mech -->|MECH_TABLES)', '<!-- mech -->\n' + tables.strip() + '\n<!-- /mech -->', s, count=1, flags=re.S)
p.write_text(s)
print(done)
