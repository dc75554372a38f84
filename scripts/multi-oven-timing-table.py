#!/usr/bin/env python3
"""The table of the multi-oven timing study's lines (results/extensions; sweeps/timing-multi-oven.toml): per
oven set-up and model, the one-oven curve (accuracy, WF; means over seeds), each oven's
accuracy (mean and minimum over ovens and seeds) and the interference against the one-oven
curve (ΔWF, ΔBP in steps: mean and range over ovens and seeds).

    python3 scripts/multi-oven-timing-table.py LINES > summary.md   (LINES: scripts/timing-study-lines.py multi-oven)
"""
import re
import sys
from collections import OrderedDict


def num(v):
    return None if v == "na" else float(v)


cells = OrderedDict()
for line in open(sys.argv[1]):
    setup, model = line.split()[:2]
    ovens = re.search(r"ovens=(\d)", setup)[1]
    mode = "async" if "asynchronous=true" in setup else "sync"
    c = cells.setdefault((f"{ovens} {mode}", model), {"sacc": [], "swf": [], "acc": [], "dwf": [], "dbp": []})
    single = re.search(r"single acc (\S+) bp \S+ wf (\S+)", line)
    c["sacc"].append(num(single[1]))
    c["swf"].append(num(single[2]))
    for o in re.finditer(r"oven\d acc (\S+) bp \S+ wf \S+ dwf (\S+) dbp (\S+)", line):
        c["acc"].append(num(o[1]))
        c["dwf"].append(num(o[2]))
        c["dbp"].append(num(o[3]))


def mean(xs):
    xs = [x for x in xs if x is not None]
    return sum(xs) / len(xs) if xs else None


def spread(xs, p):
    xs = [x for x in xs if x is not None]
    if not xs:
        return "na"
    return f"{mean(xs):+.{p}f} ({min(xs):+.{p}f} … {max(xs):+.{p}f})"


print("| set-up | model | one oven: accuracy, WF | each oven: accuracy, mean (min) | ΔWF vs one oven: mean (range) | ΔBP vs one oven, steps: mean (range) |")
print("|---|---|---|---|---|---|")
for (setup, model), c in cells.items():
    acc = [a for a in c["acc"] if a is not None]
    print(f"| {setup} | {model} | {mean(c['sacc']):.2f}, {mean(c['swf']):.3f} | {mean(acc):.3f} ({min(acc):.2f}) "
          f"| {spread(c['dwf'], 3)} | {spread(c['dbp'], 2)} |")
