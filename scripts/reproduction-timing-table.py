#!/usr/bin/env python3
"""Markdown table of the reproduction timing grid (scripts/reproduction-timing-grid.sh):
per set-up x model x context, over seeds: success, regression slope mean (min-max), BIAS,
sqrt(VAR), Weber fraction of tp, the range of mean tp/(g ts) over every ts and seed, the
fitted wm and wp (means) and how often each observer fitted best.

    python3 scripts/reproduction-timing-table.py OUT_DIR/lines.txt
"""
import collections
import re
import sys

rows = collections.OrderedDict()
for line in open(sys.argv[1]):
    head, *contexts = line.strip().split(" | ")
    setup, model, seed, _, success = head.split()[:5]
    first = " ".join(head.split()[5:])
    for ctx in [first] + contexts:
        f = ctx.split()
        key = (setup, model, f[0], f[1])
        d = dict(zip(f[2::2], f[3::2]))
        d["success"] = success
        rows.setdefault(key, []).append(d)


def num(v):
    return None if v in (None, "na") else float(v)


def stat(ds, k, p=2):
    v = [num(d.get(k)) for d in ds]
    v = [x for x in v if x is not None]
    if not v:
        return "na"
    return f"{sum(v) / len(v):.{p}f} ({min(v):.{p}f}–{max(v):.{p}f})"


def mean(ds, k, p=2):
    v = [num(d.get(k)) for d in ds]
    v = [x for x in v if x is not None]
    return "na" if not v else f"{sum(v) / len(v):.{p}f}"


print("| set-up | model | context | seeds | success | slope mean (min–max) | BIAS | √VAR | WF of tp | tp/(g·ts) over every ts and seed | wm | wp | best observer |")
print("|---|---|---|---:|---|---|---|---|---|---|---|---|---|")
for (setup, model, prior, gain), ds in rows.items():
    lo = [float(d["ratio"].split("-")[0]) for d in ds if d.get("ratio", "na") != "na"]
    hi = [float(d["ratio"].split("-")[1]) for d in ds if d.get("ratio", "na") != "na"]
    rng = f"{min(lo):.2f}–{max(hi):.2f}" if lo else "na"
    best = collections.Counter(d.get("best") for d in ds)
    best = ", ".join(f"{k} {v}" for k, v in best.most_common())
    print(f"| {setup} | {model} | {prior} {gain} | {len(ds)} | {stat(ds, 'success')} | {stat(ds, 'slope')} | "
          f"{mean(ds, 'bias')} | {mean(ds, 'sqrtvar')} | {mean(ds, 'wf')} | {rng} | {mean(ds, 'wm')} | {mean(ds, 'wp')} | {best} |")
