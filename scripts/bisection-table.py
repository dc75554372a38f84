#!/usr/bin/env python3
"""Markdown table of `scripts/bisection-check.py` output: per model and anchor pair, the mean over
seeds of anchor accuracy / BP/GM / WF (undefined WF left out of the mean), with unanswered probes.

    python3 scripts/bisection-check.py BIN OUT ... > bis.txt && python3 scripts/bisection-table.py bis.txt
"""
import re, collections, math, sys
rows=collections.defaultdict(list)
for line in open(sys.argv[1]):
    p=line.split()
    if len(p)<8 or p[0]=='model' or not re.match(r'\d+-\d+$',p[1]): continue
    rows[(p[0],p[1])].append((float(p[3]),float(p[5]),float(p[6]),'--' in p[8:]))
pairs=["4-8","6-8","4-12","6-12","4-18","6-18"]
models=[]
for (m,_) in rows:
    if m not in models: models.append(m)
print("| model | "+" | ".join(pairs)+" |"); print("|---"*(len(pairs)+1)+"|")
for m in models:
    cells=[]
    for pr in pairs:
        v=rows.get((m,pr),[])
        if not v: cells.append("–"); continue
        a=sum(x[0] for x in v)/len(v); b=[x[1] for x in v if not math.isnan(x[1])]; w=[x[2] for x in v if not math.isnan(x[2])]
        un=sum(x[3] for x in v)
        cells.append(f"{a:.2f} / {sum(b)/max(len(b),1):.2f} / {sum(w)/max(len(w),1):.3f}" + (f" ({un} unanswered)" if un else ""))
    print(f"| {m} | "+" | ".join(cells)+" |")
