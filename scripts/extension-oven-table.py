#!/usr/bin/env python3
"""Markdown table of the multi-oven jobs of a collected extensions study
(`results/<study>/jobs/MultiOven-v0/<model~variant>/seed<k>/metrics.json`): per model and
set-up, the runs, each oven's accuracy at S and L (mean over runs, min-max), each oven's
boundary over the geometric mean of S and L (mean over the fitted ovens and runs), and the
interference against the one-oven curve the protocol also plays: the change in Weber
fraction and boundary of each oven (mean over the ovens and runs where both fits exist,
with their count).

    python3 scripts/extension-oven-table.py results/extensions
"""
import glob
import json
import os
import statistics
import sys
from collections import defaultdict


def rng(values, digits=2):
    values = [v for v in values if v is not None]
    if not values:
        return "–"
    m = statistics.mean(values)
    if len(values) == 1:
        return f"{m:.{digits}f}"
    return f"{m:.{digits}f} ({min(values):.{digits}f}–{max(values):.{digits}f})"


def main(root):
    rows = defaultdict(lambda: defaultdict(list))
    for f in sorted(glob.glob(os.path.join(root, "jobs", "MultiOven-v0", "*", "seed*", "metrics.json"))):
        folder = f.split(os.sep)[-3]
        model, _, variant = folder.partition("~")
        setup = variant.replace("env.", "").replace("_", " ")
        mo = json.load(open(f)).get("multi_oven")
        if not mo:
            continue
        r = rows[(setup, model)]
        r["runs"].append(1)
        acc = [o["accuracy"] for o in mo["per_oven"] if o.get("accuracy") is not None]
        r["acc"].append(statistics.mean(acc) if acc else None)
        r["bp"].extend(o["bp_over_gm"] for o in mo["per_oven"] if o.get("bp_over_gm") is not None)
        for i in mo.get("interference", []):
            if i.get("d_wf") is not None:
                r["dwf"].append(i["d_wf"])
            if i.get("d_bp") is not None:
                r["dbp"].append(i["d_bp"])
    print("| set-up | model | runs | oven accuracy at S and L, mean over ovens (runs with a delivery at S or L) | BP / GM, every fitted oven | ΔWF against one oven (n) | ΔBP against one oven, steps (n) |")
    print("|---|---|---:|---|---|---|---|")
    for (setup, model), r in sorted(rows.items()):
        print(f"| {setup} | {model} | {len(r['runs'])} | {rng(r['acc'])} | {rng(r['bp'])} "
              f"| {rng(r['dwf'], 3)} ({len(r['dwf'])}) | {rng(r['dbp'])} ({len(r['dbp'])}) |")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/extensions")
