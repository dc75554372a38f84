#!/usr/bin/env python3
"""Scalar-property table of the timing models through the CLI.

For each model and TD in {4, 6, 9, 12, 18, 24}: `chronocooked train` on fixed interval, then
`chronocooked eval --stochastic N` (N episodes per condition; the models' own noise, seeded)
and the first-oven-check (FOC) mean, SD and CV; per model the R² of mean vs TD and of SD vs
mean (constant CV = SD proportional to the mean).

    python3 scripts/scalar-property.py BIN OUT [--models ddm,sbf] [--episodes 40] [--set noise=0.15]
"""
import argparse, json, pathlib, subprocess

TDS = [4, 6, 9, 12, 18, 24]


def r2(x, y):
    n = len(x)
    mx, my = sum(x) / n, sum(y) / n
    sxx = sum((a - mx) ** 2 for a in x)
    syy = sum((b - my) ** 2 for b in y)
    sxy = sum((a - mx) * (b - my) for a, b in zip(x, y))
    return sxy * sxy / (sxx * syy) if sxx > 0 and syy > 0 else float("nan")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bin"); ap.add_argument("out")
    ap.add_argument("--models", default="ddm,sbf,timecells-csc,timecells-ms,timecells-laplace")
    ap.add_argument("--episodes", default="40")
    ap.add_argument("--seed", default="0")
    ap.add_argument("--set", action="append", default=[], help="MODEL:key=value or key=value")
    a = ap.parse_args()
    out = pathlib.Path(a.out)
    print("| model | settings | " + " | ".join(f"TD {t} mean / SD / CV" for t in TDS) + " | R² mean~TD | R² SD~mean |")
    print("|---" * (len(TDS) + 4) + "|")
    for model in a.models.split(","):
        sets = [s.split(":", 1)[1] if ":" in s else s for s in a.set
                if ":" not in s or s.split(":", 1)[0] == model]
        means, sds, cells = [], [], []
        for td in TDS:
            run = out / f"{model}-td{td}-{'-'.join(sets) or 'default'}"
            if not (run / "summary.json").exists():
                subprocess.run([a.bin, "train", "--task", "FixedInterval-v0", "--model", model,
                                "--seed", a.seed, "--out", str(run), "--quiet",
                                f"--set=env.td={td}", *[f"--set={s}" for s in sets]],
                               check=True, capture_output=True)
            subprocess.run([a.bin, "eval", "--run", str(run), "--out", str(run) + "-eval",
                            "--stochastic", a.episodes, "--seed", a.seed],
                           check=True, capture_output=True)
            foc = json.load(open(str(run) + "-eval/metrics.json"))["fi"]["foc"]
            f = next(x for x in foc if x["td"] == td)
            means.append(f["mean"]); sds.append(f["sd"])
            cells.append(f"{f['mean']:.1f} / {f['sd']:.2f} / {f['sd'] / f['mean']:.2f}")
        print(f"| {model} | {' '.join(sets) or 'default'} | " + " | ".join(cells)
              + f" | {r2(TDS, means):.3f} | {r2(means, sds):.3f} |")


main()
