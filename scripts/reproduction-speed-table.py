#!/usr/bin/env python3
"""Markdown table of the timing models' KiNeT analysis after Set (lines from
`scripts/reproduction-speed-grid.sh`): per model, clock population and prior, the scaling
index (1: time-stretched trajectories, timing by speed; 0: one trajectory run at a fixed
speed) and the order of the initial states at Set by ts, mean (min-max) over seeds.

    python3 scripts/reproduction-speed-table.py DIR/lines.jsonl
"""
import json
import statistics
import sys
from collections import defaultdict

# The population that carries each model's clock.
CLOCK = {"ddm": "accumulator", "sbf": "oscillators", "timecells-csc": "time_cells",
         "timecells-ms": "time_cells", "timecells-laplace": "time_cells"}


def cell(values):
    values = [v for v in values if v is not None]
    if not values:
        return "–"
    return f"{statistics.mean(values):.2f} ({min(values):.2f} – {max(values):.2f})"


def main(path):
    rows = defaultdict(list)
    for line in open(path):
        r = json.loads(line)
        if CLOCK.get(r["model"]) == r["population"]:
            rows[(r["model"], r["population"], r["prior"])].append(r)
    print("| model | population | prior | seeds | units | scaling index, mean (min – max) | initial-state order by ts |")
    print("|---|---|---:|---:|---:|---|---|")
    for (model, pop, prior), rs in sorted(rows.items()):
        print(f"| {model} | {pop} | {prior} | {len(rs)} | {rs[0]['units']} | "
              f"{cell([r['scaling_index'] for r in rs])} | {cell([r['initial_order'] for r in rs])} |")


if __name__ == "__main__":
    main(sys.argv[1])
