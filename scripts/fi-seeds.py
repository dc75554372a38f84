#!/usr/bin/env python3
"""First oven checks of one timing model on fixed interval over TDs and training seeds.

For each seed and TD: `chronocooked train` (default settings plus any `--set`), then
`chronocooked eval` with the reference protocol (`ref`) and with 40 stochastic episodes
(`sto`); prints FOC/TD and the FOC CV per TD. Resumable (trained runs are kept).

    python3 scripts/fi-seeds.py BIN OUT MODEL TDS SEEDS [key=value ...]
    python3 scripts/fi-seeds.py target/release/chronocooked out sbf 5,8,20 1,2,3
"""
import json, pathlib, subprocess, sys


def main():
    b, out, model, tds, seeds = sys.argv[1:6]
    sets = sys.argv[6:]
    out = pathlib.Path(out)
    for seed in seeds.split(","):
        cells = []
        for td in map(int, tds.split(",")):
            run = out / f"{model}-td{td}-s{seed}-{'-'.join(sets) or 'default'}"
            if not (run / "summary.json").exists():
                subprocess.run([b, "train", "--task", "FixedInterval-v0", "--model", model,
                                "--seed", seed, "--out", str(run), "--quiet",
                                f"--set=env.td={td}", *[f"--set={s}" for s in sets]],
                               check=True, capture_output=True)
            for mode, extra in (("ref", []), ("sto", ["--stochastic", "40"])):
                ev = f"{run}-{mode}"
                subprocess.run([b, "eval", "--run", str(run), "--out", ev, "--seed", seed, *extra],
                               check=True, capture_output=True)
                f = [x for x in json.load(open(ev + "/metrics.json"))["fi"]["foc"] if x["td"] == td][0]
                cells.append(f"TD{td} {mode} {f['mean'] / td:.2f}/{f['cv']:.2f}")
        print(model, seed, " ".join(sets), " | ".join(cells), flush=True)


main()
