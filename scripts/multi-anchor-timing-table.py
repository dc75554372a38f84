#!/usr/bin/env python3
"""The table of `scripts/multi-anchor-timing-grid.sh`'s lines (RESULTS "Extensions"): per
anchor set and model, the anchor accuracy over seeds, each boundary's mean BP with the
pair's GM and AM, and in how many single runs the GM lies inside the run's own 95% interval
of the boundary (over every boundary of every seed).

    python3 scripts/multi-anchor-timing-table.py OUT_DIR/lines.txt > OUT_DIR/summary.md
"""
import re
import sys
from collections import OrderedDict

cells = OrderedDict()
for line in open(sys.argv[1]):
    parts = line.split(" ", 5)
    anchors, model, acc = parts[0], parts[1], float(parts[4])
    fits = parts[5].strip().split(" | ") if len(parts) > 5 else []
    cell = cells.setdefault((anchors, model), {"acc": [], "bounds": {}, "inside": 0, "fits": 0})
    cell["acc"].append(acc)
    for k, f in enumerate(fits):
        m = re.match(r"([\d.]+)\[([\d.]+),([\d.]+)\]gm([\d.]+)([* ])am([\d.]+)", f)
        b = cell["bounds"].setdefault(k, {"bp": [], "gm": None, "am": None})
        if not m:
            continue
        bp, gm, star, am = float(m[1]), float(m[4]), m[5], float(m[6])
        b["bp"].append(bp)
        b["gm"], b["am"] = gm, am
        cell["fits"] += 1
        cell["inside"] += star == "*"

print("| anchors | model | anchor accuracy: mean (min–max), seeds | each boundary: mean BP over seeds (GM / AM) | GM inside the run's 95% interval |")
print("|---|---|---|---|---|")
for (anchors, model), c in cells.items():
    acc = c["acc"]
    bounds = []
    for k in sorted(c["bounds"]):
        b = c["bounds"][k]
        if not b["bp"]:
            bounds.append("no fit")
            continue
        note = "" if len(b["bp"]) == len(acc) else f" [{len(b['bp'])} fits]"
        bounds.append(f"{sum(b['bp']) / len(b['bp']):.2f} ({b['gm']:.2f} / {b['am']:.1f}){note}")
    print(f"| {anchors} | {model} | {sum(acc) / len(acc):.3f} ({min(acc):.3f}–{max(acc):.3f}) "
          f"| {'; '.join(bounds)} | {c['inside']} of {c['fits']} |")
