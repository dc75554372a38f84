#!/usr/bin/env python3
"""Summarises `chronocooked paper check-held-out`'s held-out.csv for RESULTS.md (stdlib only):
verdict counts per model, the share of judged statistics inside the 95% range for a new run
(a calibrated range holds about 95%), and every statistic outside it or without a value where
most study runs have one.

    python3 scripts/heldout-summary.py results/paper-core-heldout/held-out.csv
"""
import collections
import csv
import sys

path = sys.argv[1] if len(sys.argv) > 1 else "results/paper-core-heldout/held-out.csv"
rows = list(csv.DictReader(open(path)))
jobs = len({r["id"] for r in rows})
count = collections.Counter((r["model"], r["verdict"]) for r in rows)
inside = sum(r["verdict"] == "inside" for r in rows)
outside = sum(r["verdict"] == "outside" for r in rows)
print(f"{jobs} held-out jobs, {len(rows)} statistics: {inside} of {inside + outside} judged inside "
      f"({100 * inside / (inside + outside):.0f}%), {outside} outside, "
      f"{sum(r['verdict'] == 'no-value' for r in rows)} without a held-out value\n")
print("| model | jobs | inside | outside | no value |")
print("|---|---:|---:|---:|---:|")
for m in sorted({r["model"] for r in rows}):
    n_jobs = len({r["id"] for r in rows if r["model"] == m})
    print(f"| {m} | {n_jobs} | {count[(m, 'inside')]} | {count[(m, 'outside')]} | {count[(m, 'no-value')]} |")
print("\n| job | statistic | held-out | study mean ± SD (runs with a value of all) | 95% range | verdict |")
print("|---|---|---:|---|---|---|")
for r in rows:
    unlike = r["verdict"] == "no-value" and int(r["n"]) * 2 > int(r["runs"])
    if r["verdict"] == "outside" or unlike:
        f = lambda x: "–" if x in ("", "NaN", "nan") else f"{float(x):.3f}"
        job = r["id"].split("/")
        print(f"| {job[0].removesuffix('-v0')} {job[1]} {job[2]} | {r['statistic']} | {f(r['value'])} | "
              f"{f(r['mean'])} ± {f(r['sd'])} ({r['n']} of {r['runs']}) | {f(r['lo'])} … {f(r['hi'])} | {r['verdict']} |")
