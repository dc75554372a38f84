#!/usr/bin/env python3
"""Held-out style bisection check of the timing models through the CLI.

Trains each model on each anchor pair with `chronocooked train`, evaluates it with
`chronocooked eval`, and prints anchor accuracy, the largest drop of P(long) between
consecutive probes, and BP / GM (the issue-17 criteria: anchors >= 0.95, drop <= 0.25,
BP in [0.8, 1.3] GM).

    python3 scripts/bisection-check.py BIN OUT [--models ddm,sbf] [--pairs 6-8,4-18] [--seeds 0,1]
"""
import argparse, json, math, pathlib, subprocess

PAIRS = ["4-8", "6-8", "4-12", "6-12", "4-18", "6-18"]
MODELS = ["ddm", "sbf", "timecells-ms", "timecells-laplace"]

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bin"); ap.add_argument("out")
    ap.add_argument("--models", default=",".join(MODELS))
    ap.add_argument("--pairs", default=",".join(PAIRS))
    ap.add_argument("--seeds", default="0")
    ap.add_argument("--set", action="append", default=[])
    a = ap.parse_args()
    out = pathlib.Path(a.out)
    bad = 0
    print(f"{'model':18} {'pair':5} seed anchors max_drop  BP/GM    WF  ok  p_long")
    for model in a.models.split(","):
        for pair in a.pairs.split(","):
            s, l = map(int, pair.split("-"))
            for seed in a.seeds.split(","):
                run = out / f"{model}-{pair}-s{seed}"
                sets = [f"--set=env.short={s}", f"--set=env.long={l}"] + [f"--set={x}" for x in a.set]
                if not (run / "summary.json").exists():  # resumable
                    subprocess.run([a.bin, "train", "--task", "Bisection-v0", "--model", model,
                                    "--seed", seed, "--out", str(run), "--quiet", *sets],
                                   check=True, capture_output=True)
                subprocess.run([a.bin, "eval", "--run", str(run), "--out", str(run) + "-eval"],
                               check=True, capture_output=True)
                b = json.load(open(str(run) + "-eval/metrics.json"))["bisection"]
                p = b["p_long"]
                v = [x for x in p if x is not None]  # probes with no valid choice are skipped
                drop = max([0.0] + [v[i] - v[i + 1] for i in range(len(v) - 1)])
                ok_probes = len(v) == len(p)
                # A step-shaped curve has no measurable WF: the fit writes null (undefined).
                bp = (b.get("fit") or {}).get("bp")
                wf = (b.get("fit") or {}).get("wf")
                bp = float("nan") if bp is None else bp
                wf = float("nan") if wf is None else wf
                ratio = bp / math.sqrt(s * l)
                acc = b["anchor_accuracy"]
                acc = float("nan") if acc is None else acc
                ok = ok_probes and acc >= 0.95 and drop <= 0.25 and 0.8 <= ratio <= 1.3
                bad += not ok
                print(f"{model:18} {pair:5} {seed:>4} {acc:7.3f} {drop:8.3f} {ratio:6.2f} {wf:5.3f} "
                      f"{'yes' if ok else 'NO':>3}  {' '.join('--' if x is None else f'{x:.2f}' for x in p)}")
    print(f"{bad} failing")

main()
