#!/usr/bin/env python3
"""Every timing model on every registered task, through the CLI (issue 17's task matrix).

Trains each model on each task setting with `chronocooked train` (default episodes of the
task), evaluates it with `chronocooked eval` (the reference protocol) and prints the
success rate: FI and multi-timer overall (multi-timer also per TD), bisection anchor
accuracy, uncertainty normal / never-ready ovens. Resumable (finished runs are kept).

    python3 scripts/task-matrix.py BIN OUT [--models ddm,sbf] [--tasks mt-lower,unc] [--seeds 0,1]
"""
import argparse, json, pathlib, subprocess

MODELS = ["ddm", "sbf", "timecells-csc", "timecells-ms", "timecells-laplace", "timecells-presence"]
# name -> (task id, settings)
TASKS = {
    "fi": ("FixedInterval-v0", []),
    "pi": ("PeakInterval-v0", []),
    "bisection": ("Bisection-v0", []),
    "mt-default": ("MultiTimer-v0", []),
    "mt-lower": ("MultiTimer-v0", ["env.mode=lower_bounded", "env.num_timers=5"]),
    "mt-exact": ("MultiTimer-v0", ["env.mode=exact", "env.num_timers=5"]),
    "mt-exact-cat": ("MultiTimer-v0", ["env.mode=exact", "env.num_timers=5", "env.cue=categorical"]),
    "mt-exact-under3": ("MultiTimer-v0", ["env.mode=exact", "env.num_timers=5", "env.under_buffer=3"]),
    "dual": ("DualTask-v0", []),
    "unc": ("Uncertainty-v0", []),
}

def summary(task, m):
    """(headline success, per-TD detail) from an eval's metrics.json."""
    if task == "Bisection-v0":
        return f"{m['bisection']['anchor_accuracy']:.2f}", ""
    conds = m["conditions"]
    if task == "Uncertainty-v0":
        def rate(never):
            c = [x for x in conds if bool(x.get("never_ready")) == never]
            n = sum(x["episodes"] for x in c)
            return sum(x["success_rate"] * x["episodes"] for x in c) / max(n, 1)
        return f"{rate(False):.2f} / {rate(True):.2f}", ""
    by_td = {}
    for c in conds:
        if c["kind"] in ("fi", "pi", "multi_timer", "dual", "train"):
            by_td.setdefault(c["td"], []).append((c["success_rate"], c["episodes"]))
    per = " ".join(f"TD{td}:{sum(r * n for r, n in v) / sum(n for _, n in v):.2f}"
                   for td, v in sorted(by_td.items()))
    return f"{m['success_rate']:.2f}", per

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bin"); ap.add_argument("out")
    ap.add_argument("--models", default=",".join(MODELS))
    ap.add_argument("--tasks", default=",".join(TASKS))
    ap.add_argument("--seeds", default="0")
    ap.add_argument("--set", action="append", default=[], help="extra train --set for every run")
    a = ap.parse_args()
    out = pathlib.Path(a.out)
    print(f"{'model':18} {'task':16} seed  success  per TD")
    for model in a.models.split(","):
        for name in a.tasks.split(","):
            task, sets = TASKS[name]
            for seed in a.seeds.split(","):
                run = out / f"{model}-{name}-s{seed}"
                args = [f"--set={x}" for x in sets + a.set]
                if not (run / "summary.json").exists():
                    subprocess.run([a.bin, "train", "--task", task, "--model", model, "--seed", seed,
                                    "--out", str(run), "--quiet", *args], check=True, capture_output=True)
                ev = pathlib.Path(str(run) + "-eval")
                if not (ev / "metrics.json").exists():
                    subprocess.run([a.bin, "eval", "--run", str(run), "--out", str(ev)],
                                   check=True, capture_output=True)
                m = json.load(open(ev / "metrics.json"))
                s, per = summary(task, m)
                print(f"{model:18} {name:16} {seed:>4}  {s:7}  {per}", flush=True)

main()
