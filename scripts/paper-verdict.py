#!/usr/bin/env python3
"""Prints the numbers RESULTS.md's verdict paragraph quotes, from a study's comparison.csv
and agreement.json (stdlib only), so the paragraph can be refreshed after every analysis:

    python3 scripts/paper-verdict.py results/paper-core

Counts follow `paper analyse`: agree = yes / (yes + no); n/a and both-NaN rows are left out
of the rate and counted apart.
"""
import csv
import json
import sys
from collections import defaultdict

root = sys.argv[1] if len(sys.argv) > 1 else "results/paper-core"
rows = list(csv.DictReader(open(f"{root}/comparison.csv")))


def model_of(r):
    # fi_r2 rows name the regression in `column` and the model in `row`.
    return r["row"] if r["table"].startswith(("fi_r2", "appendix_fi_r2")) else r["column"]


def family(r):
    t = r["table"]
    return "bisection" if t.startswith("bisection") else "fi" if t.startswith("fi") else t


def tally(rs, key):
    yes = sum(r[key] == "yes" for r in rs)
    no = sum(r[key] == "no" for r in rs)
    both = sum(r[key] == "both-nan" for r in rs)
    na = sum(r[key] == "n/a" for r in rs)
    return f"{yes} of {yes + no}" + (f" ({both} both NaN)" if both else "") + (f" ({na} n/a)" if na else "")


main = [r for r in rows if not r["table"].startswith("appendix")]
printed = [r for r in main if r["source"] == "paper"]
print(f"printed in the paper ({len(printed)}): z {tally(printed, 'agree_z')}; old {tally(printed, 'agree')}")
by = defaultdict(list)
for r in printed:
    by[model_of(r)].append(r)
for m, rs in sorted(by.items()):
    fam = defaultdict(list)
    for r in rs:
        fam[family(r)].append(r)
    parts = "; ".join(f"{f} z {tally(x, 'agree_z')}, old {tally(x, 'agree')}" for f, x in sorted(fam.items()))
    print(f"  {m} ({len(rs)}): z {tally(rs, 'agree_z')}, old {tally(rs, 'agree')} — {parts}")
nb = [r for r in main if r["source"] == "notebook"]
print(f"notebook-only ({len(nb)}): z {tally(nb, 'agree_z')}; old {tally(nb, 'agree')}")
app = [r for r in rows if r["table"].startswith("appendix")]
app_p = [r for r in app if r["source"] == "paper"]
print(f"appendix printed ({len(app_p)}): z {tally(app_p, 'agree_z')}; old {tally(app_p, 'agree')}")
means = [r for r in app if r["table"] in ("appendix_wf", "appendix_dl")]
finite = sum(r["lab_mean"] not in ("NaN", "nan", "") for r in means)
print(f"appendix WF/DL means: {len(means)} run, {finite} with a finite lab value")

agreement = json.load(open(f"{root}/agreement.json"))
print("negative control (source paper):")
for c in agreement["negative_control"]:
    if c["source"] == "paper" and c["rows"]:
        tag = "matched" if c["matched"] else "mismatched"
        n = c["yes"] + c["no"]
        print(f"  {c['pairing']} [{tag}] {c['rule']}: {c['yes']} of {n} ({100 * c['yes'] / n:.0f}%)" if n else
              f"  {c['pairing']} [{tag}] {c['rule']}: no judged rows")
