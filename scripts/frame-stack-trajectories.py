#!/usr/bin/env python3
"""Where the frame-stack control keeps time: the agent's route through the kitchen.

    python3 scripts/frame-stack-trajectories.py [SWEEP_OUT] [--k 4]

SWEEP_OUT (default lab-out/frame-stack-control) is the output of
`chronocooked sweep sweeps/frame-stack-control.toml --out SWEEP_OUT`; the script reads each
job's `eval/records.jsonl` (every greedy evaluation episode, step by step) and prints a
Markdown table. Standard library only.

A `cnn-mlp-stack<k>` policy sees the last k observations and nothing else, so whatever it
knows about the time since the onion went in must be in those k frames. While the oven is
on, the frames differ only in where the agent is (the oven shows "on" at every step until it
turns "ready"). The table measures, per job:

* `t | window`: how well the agent's own positions in the last k frames tell the time
  elapsed since the put (steps 1 … d−1 of every probe episode while the oven is on; the
  share of steps whose window's most frequent elapsed time is the true one). An agent that
  waits in one place scores about 1 / (number of elapsed times); one that walks a fixed route
  scores up to 1.
* bisection only, at the step the oven turns ready (the first frame that shows "ready"):
  `choice | window`, the share of delivered episodes whose counter is the most frequent
  counter among episodes with the same k-frame window of positions; `choice | cell`, the
  same from the agent's cell at that step alone; `choice | start`, the same from the start
  cell alone (the control: what the agent could know without walking).

`choice | window` = 1 means the category is a function of where the agent walked in the
last k steps, which the policy sees: the route is the clock.
"""
import argparse
import collections
import glob
import json
import os
import sys


def purity(pairs):
    """Share of (key, value) pairs whose value is the most frequent value of their key."""
    groups = collections.defaultdict(collections.Counter)
    for key, value in pairs:
        groups[key][value] += 1
    hits = sum(c.most_common(1)[0][1] for c in groups.values())
    return hits / len(pairs) if pairs else float("nan")


def window(infos, end, k):
    """The agent's cells in the k frames ending at step index `end` (earlier ones clipped)."""
    return tuple(tuple(infos[j]["agent"]) for j in range(max(0, end - k + 1), end + 1))


def job_rows(path, k):
    """Measures of one job's evaluation records (see the module docstring)."""
    elapsed, by_window, by_cell, by_start = [], [], [], []
    delivered = episodes = 0
    with open(path) as f:
        for line in f:
            record = json.loads(line)
            episode, infos = record["episode"], record["episode"]["infos"]
            episodes += 1
            put = next((i for i, x in enumerate(infos) if "onion_in" in x["events"]), None)
            if put is None:
                continue
            for i in range(put + 1, len(infos)):
                if infos[i]["oven_state"] != 1:
                    break
                elapsed.append((window(infos, i, k), i - put))
            choice = next((x["counter"] for x in infos if x["counter"]), None)
            ready = next((i for i in range(put, len(infos)) if infos[i]["oven_state"] == 2), None)
            if choice is None or ready is None:
                continue
            delivered += 1
            by_window.append((window(infos, ready, k), choice))
            by_cell.append((tuple(infos[ready]["agent"]), choice))
            by_start.append((tuple(episode["start"]), choice))
    return {
        "episodes": episodes,
        "delivered": delivered,
        "t_window": purity(elapsed),
        "choice_window": purity(by_window),
        "choice_cell": purity(by_cell),
        "choice_start": purity(by_start),
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("sweep_out", nargs="?", default="lab-out/frame-stack-control")
    parser.add_argument("--k", type=int, default=4, help="frames in the policy's window")
    args = parser.parse_args()
    paths = sorted(glob.glob(os.path.join(args.sweep_out, "*", "*", "seed*", "eval", "records.jsonl")))
    if not paths:
        sys.exit(f"error: no */*/seed*/eval/records.jsonl under {args.sweep_out} "
                 "(run `chronocooked sweep sweeps/frame-stack-control.toml --out DIR` first)")
    print(f"| task | condition | seed | t \\| window | choice \\| window | choice \\| cell | choice \\| start |")
    print("|---|---|---|---|---|---|---|")
    for path in paths:
        seed_dir = os.path.dirname(os.path.dirname(path))
        condition_dir = os.path.dirname(seed_dir)
        task = os.path.basename(os.path.dirname(condition_dir))
        condition = os.path.basename(condition_dir).split("~", 1)[-1]
        m = job_rows(path, args.k)
        if m["t_window"] != m["t_window"]:
            continue  # no onion put in any episode (the reproduction task has no oven put)
        fmt = lambda x: "–" if x != x else f"{x:.2f}"  # noqa: E731  (NaN as a dash)
        bisection = task.startswith("Bisection")
        cells = [fmt(m["choice_window"]), fmt(m["choice_cell"]), fmt(m["choice_start"])] if bisection else ["", "", ""]
        print(f"| {task} | {condition} | {os.path.basename(seed_dir)[4:]} | {fmt(m['t_window'])} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
