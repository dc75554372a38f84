#!/usr/bin/env python3
"""Markdown tables of a PPO reproduction study collected by `chronocooked paper collect`
(`results/<study>/jobs/<task>/<model>/seed<k>/`): behaviour per model and prior (evaluation
success, slope of tp on ts, the range of mean tp/ts over every ts and seed, how many seeds
keep tp/ts within 0.8-1.2 at every ts, BIAS, sqrt(VAR), the fitted wm and wp and the best
observer), then KiNeT after Set per model, population and prior (scaling index: 1 for
time-stretched trajectories, 0 for a fixed-speed clock; order of the states at Set by ts),
mean (min-max) over seeds.

    python3 scripts/reproduction-ppo-table.py results/reproduction/ppo-fast
"""
import glob
import json
import os
import statistics
import sys
from collections import Counter, defaultdict


def cell(values, digits=2):
    values = [v for v in values if v is not None]
    if not values:
        return "–"
    m, lo, hi = statistics.mean(values), min(values), max(values)
    return f"{m:.{digits}f} ({lo:.{digits}f} – {hi:.{digits}f})"


def main(root):
    behaviour = defaultdict(list)
    speed = defaultdict(list)
    for job in sorted(glob.glob(os.path.join(root, "jobs", "*", "*", "seed*"))):
        model = os.path.basename(os.path.dirname(job))
        metrics = os.path.join(job, "metrics.json")
        if not os.path.exists(metrics):
            continue
        m = json.load(open(metrics))
        for c in m["reproduction"]["contexts"]:
            behaviour[(model, c["prior"], c["gain"])].append((m["success_rate"], c))
        summary = os.path.join(job, "activity.summary.json")
        if os.path.exists(summary):
            for s in json.load(open(summary)):
                for p in s.get("production_speed", []):
                    speed[(model, s["population"], p["prior"])].append(p)
    print("| model | prior | gain | seeds | success | slope | tp/ts over every ts and seed |"
          " seeds within 0.8–1.2 at every ts | BIAS | √VAR | wm | wp | best observer |")
    print("|---|---:|---:|---:|---|---|---|---:|---|---|---|---|---|")
    for (model, prior, gain), runs in sorted(behaviour.items()):
        ratios = [[r[1] for r in c["ratio"]] for _, c in runs]
        flat = [r for rs in ratios for r in rs]
        within = sum(1 for rs in ratios if rs and all(0.8 <= r <= 1.2 for r in rs))
        obs = [c.get("observer") for _, c in runs]
        best = Counter(o["best"] if o else "na" for o in obs)
        print(f"| {model} | {prior} | {gain:g} | {len(runs)} | {cell([s for s, _ in runs])} | "
              f"{cell([c['slope'] for _, c in runs])} | "
              f"{min(flat):.2f}–{max(flat):.2f} | {within} | "
              f"{cell([c['bias'] for _, c in runs])} | {cell([c['sqrt_var'] for _, c in runs])} | "
              f"{cell([o['wm'] if o else None for o in obs])} | "
              f"{cell([o['wp'] if o else None for o in obs])} | "
              f"{', '.join(f'{k} {v}' for k, v in best.most_common())} |")
    print()
    print("| model | population | prior | seeds | scaling index | initial-state order by ts |")
    print("|---|---|---:|---:|---|---|")
    for (model, pop, prior), runs in sorted(speed.items()):
        if pop == "value":
            continue
        print(f"| {model} | {pop} | {prior} | {len(runs)} | "
              f"{cell([p['scaling_index'] for p in runs])} | "
              f"{cell([p['initial_order'] for p in runs])} |")


if __name__ == "__main__":
    main(sys.argv[1])
