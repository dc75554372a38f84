#!/usr/bin/env python3
"""Per-level evaluation of the extension curricula (multi-anchor 2 -> 3 -> 4 counters,
multi-oven 1 -> 2 -> 3 ovens) from a collected results folder's `levels.csv` files.

For every PPO job it reads the levels its run passed and, for each level's policy playing
its own level's task, the accuracy at the anchors: the share of episodes at a probe equal to
an active anchor (multi-anchor) or to S / L (multi-oven, every multi-oven condition) that
were delivered to the right counter. It prints one Markdown row per model and set-up:
levels reached over the seeds, the last level's accuracy on its own task (mean, min-max),
and the final policy's accuracy at the anchors of the full task (from `episodes.csv`, the
protocol's evaluation) for comparison.

    python3 scripts/extension-levels-table.py results/extensions
"""
import csv
import glob
import os
import statistics
import sys
from collections import defaultdict


def anchors_of(env):
    """The active anchors of a job's task at a level (multi-anchor) or (S, L) multi-oven.
    `env` is the job's task parameters: a map of typed values (`{"anchors": [4, 8, 16]}`),
    or in jobs collected before the map a list of `key=value` texts."""
    if isinstance(env, dict):
        kv = {k: ",".join(map(str, v)) if isinstance(v, list) else str(v) for k, v in env.items()}
    else:
        kv = dict(e.split("=", 1) for e in env)
    if "anchors" in kv:
        return [int(a) for a in kv["anchors"].split(",")]
    return [int(kv.get("short", 4)), int(kv.get("long", 12))]


def accuracy(rows, tds, kind):
    hits = [r["success"] == "true" for r in rows if int(r["td"]) in tds and r["kind"] == kind]
    return (sum(hits) / len(hits)) if hits else float("nan"), len(hits)


def main(root):
    table = defaultdict(list)
    for levels_path in sorted(glob.glob(os.path.join(root, "jobs", "*", "*", "seed*", "levels.csv"))):
        job = os.path.dirname(levels_path)
        task = job.split(os.sep)[-3]
        model, _, variant = job.split(os.sep)[-2].partition("~")
        env = open(os.path.join(job, "job.json")).read()
        import json

        spec = json.loads(env)
        anchors = anchors_of(spec["env"])
        rows = list(csv.DictReader(open(levels_path)))
        levels = sorted({int(r["level"]) for r in rows})
        last = levels[-1]
        if task == "MultiAnchor-v0":
            kind, own = "multi_anchor", anchors[: 2 + last]
        else:
            kind, own = "multi_oven", anchors
        acc, n = accuracy([r for r in rows if int(r["level"]) == last], set(own), kind)
        final_rows = list(csv.DictReader(open(os.path.join(job, "episodes.csv"))))
        final_acc, _ = accuracy(final_rows, set(anchors), kind)
        table[(task, variant, model)].append((last, acc, final_acc, n))
    print("| task | set-up | model | seeds | last level reached (per seed) | last level's policy on its own task: accuracy at the anchors, mean (min–max) | final policy on the full task: accuracy at the anchors, mean |")
    print("|---|---|---|---:|---|---|---|")
    for (task, variant, model), runs in sorted(table.items()):
        lv = ", ".join(str(r[0]) for r in runs)
        accs = [r[1] for r in runs]
        finals = [r[2] for r in runs]
        print(
            f"| {task} | {variant.replace('env.', '').replace('_', ' ')} | {model} | {len(runs)} | {lv} | "
            f"{statistics.mean(accs):.2f} ({min(accs):.2f}–{max(accs):.2f}) | {statistics.mean(finals):.2f} |"
        )


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/extensions")
