#!/usr/bin/env python3
"""Markdown table of a `scripts/task-matrix.py` output folder (seed 0): success per model and task
from each evaluation's metrics.json (FI condition, bisection anchors, multi-timer mean over
TDs 3-15 with TDs below 0.9 listed for the lower-bounded variant, dual, uncertainty normal / never-ready).

    python3 scripts/task-matrix-table.py OUT
"""
import json, sys, pathlib
out = pathlib.Path(sys.argv[1])
models = ["ddm","sbf","timecells-csc","timecells-ms","timecells-laplace","timecells-presence"]
tasks = ["fi","bisection","mt-lower","mt-exact","mt-exact-cat","dual","unc"]
print("| model | FI | bisection | multi-timer lower-bounded | multi-timer exact | exact, categorical cue | dual | uncertainty |")
print("|---"*8+"|")
for m in models:
    cells=[]
    for t in tasks:
        f = out/f"{m}-{t}-s0-eval/metrics.json"
        if not f.exists(): cells.append("–"); continue
        x = json.load(open(f)); conds = x["conditions"]
        def rate(sel):
            c=[k for k in conds if sel(k)]; n=sum(k["episodes"] for k in c)
            return sum(k["success_rate"]*k["episodes"] for k in c)/max(n,1)
        if t=="fi": cells.append(f"{rate(lambda k:k['kind']=='fi'):.2f}")
        elif t=="bisection": cells.append(f"{x['bisection']['anchor_accuracy']:.2f}")
        elif t.startswith("mt"):
            per={}
            for k in conds:
                if k["kind"]=="multi_timer" and k["td"] in (3,6,9,12,15): per[k["td"]]=k["success_rate"]
            cells.append(f"{sum(per.values())/max(len(per),1):.2f}" + (" ("+", ".join(f"{td}: {v:.2f}" for td,v in sorted(per.items()) if v<0.9)+")" if any(v<0.9 for v in per.values()) and t=="mt-lower" else ""))
        elif t=="dual": cells.append(f"{rate(lambda k:k['kind']=='dual'):.2f}")
        elif t=="unc": cells.append(f"{rate(lambda k:k.get('never_ready') is False):.2f} / {rate(lambda k:k.get('never_ready') is True):.2f}")
    print(f"| {m} | "+" | ".join(cells)+" |")
