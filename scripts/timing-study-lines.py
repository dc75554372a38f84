#!/usr/bin/env python3
"""The lines of a timing-model study, one per job, from its sweep (or its collected results):
what `scripts/multi-anchor-timing-table.py` and `scripts/multi-oven-timing-table.py`
tabulate.

    python3 scripts/timing-study-lines.py multi-anchor SWEEP_FILE DIR > lines.txt
    python3 scripts/timing-study-lines.py multi-oven SWEEP_FILE DIR > lines.txt
    python3 scripts/timing-study-lines.py reproduction SWEEP_FILE DIR > lines.txt
    python3 scripts/timing-study-lines.py reproduction-heldout SWEEP_FILE DIR > heldout-priors.txt
    python3 scripts/timing-study-lines.py categories SWEEP_FILE DIR > lines.txt
    python3 scripts/timing-study-lines.py reproduction-speed SWEEP_FILE DIR > lines.jsonl

* multi-anchor (sweeps/timing-multi-anchor*.toml): anchor set, model, seed, anchor accuracy
  and each boundary's fit (BP [95% CI], the pair's GM and AM, each marked `*` when inside the
  interval, WF);
* multi-oven (sweeps/timing-multi-oven.toml): set-up, model, seed, success, the one-oven
  curve (accuracy, BP, WF), then per oven its accuracy, BP, WF and the interference against
  the one-oven curve (ΔWF, ΔBP);
* reproduction (sweeps/timing-reproduction.toml, with sweeps/timing-reproduction-ddm-memory.toml
  run into the same DIR): set-up (`default`, `ddm-rate0.5`, `gains`), model, seed, success,
  then per context (prior, gain) the slope of tp on ts, BIAS, sqrt(VAR), the Weber fraction
  of tp, the range of mean tp/(g ts) over ts, and the best observer with its wm and wp
  (fitted at gain 1 only);
* reproduction-heldout (sweeps/timing-reproduction-heldout-priors.toml): set-up (`inter`: the
  intermediate prior alone; `custom`: priors 10-16 and 15-21), run name, evaluation success,
  then per prior its slope and the mean tp/ts at each ts in order.

* categories (sweeps/categories-range.toml): per model, seed and TD, each recorded
  population's unit categories on probe trials (`model seed S TD T population: N units:
  counts`; readouts left out);
* reproduction-speed (sweeps/reproduction-speed.toml): one JSON line per run, population and
  prior with the recorded summary's `production_speed` (KiNeT after Set).

DIR is the sweep's output (`chronocooked sweep SWEEP_FILE --out DIR`) or its compact results
(`chronocooked paper collect DIR --out RESULTS`). Lines come in the sweep file's order: its
variants as listed, then models as its `models` list them, then seeds. Standard library only.
"""
import json
import os
import re
import sys


def listed(text, key):
    """The items of the sweep file's top-level list `key`."""
    return re.findall(r'[-\w.]+', re.search(rf"^{key}\s*=\s*\[(.*?)\]", text, re.S | re.M).group(1))


def variants(text):
    """The `task_variants` entries in order, each as `(key, value)` pairs without `env.`."""
    body = text[text.index("[task_variants]"):]
    out = []
    for v in re.findall(r"\[([^\[\]]*\"env\.[^\[\]]*)\]", body):
        out.append(tuple(tuple(kv[len("env."):].split("=", 1)) for kv in re.findall(r'"(env\.[^"]+)"', v)))
    return out


def jobs(root):
    """(job.json, metrics.json) of every finished job under `root` (a sweep output or results)."""
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames.sort()
        if "job.json" not in filenames:
            continue
        for metrics in (os.path.join(dirpath, "eval", "metrics.json"), os.path.join(dirpath, "metrics.json")):
            if os.path.isfile(metrics):
                yield os.path.join(dirpath, "job.json"), metrics
                break


def text_of(v):
    """A parameter's value as `--set` writes it: lists comma-joined, booleans lower-case."""
    if isinstance(v, bool):
        return str(v).lower()
    if isinstance(v, list):
        return ",".join(text_of(x) for x in v)
    return str(v)


def anchor_line(all_m):
    m = all_m["multi_anchor"]
    out = []
    for b in m["boundaries"]:
        f = b["fit"]
        if f is None or f.get("bp_ci") is None:
            out.append("nofit")
            continue
        lo, hi = f["bp_ci"]
        g, a = b["gm"], b["am"]
        out.append(f"{f['bp']:.2f}[{lo:.2f},{hi:.2f}]gm{g:.2f}{'*' if lo <= g <= hi else ' '}"
                   f"am{a:.1f}{'*' if lo <= a <= hi else ' '}wf{f['wf']:.2f}")
    return f"acc {m['anchor_accuracy']:.3f} " + " | ".join(out)


def oven_line(all_m):
    m = all_m["multi_oven"]
    fmt = lambda v, p=2: "na" if v is None else f"{v:.{p}f}"  # noqa: E731
    single = m["single"]
    sf = single.get("fit") if isinstance(single, dict) else None
    out = [f"single acc {fmt(single.get('accuracy'))} bp {fmt(sf and sf['bp'])} wf {fmt(sf and sf['wf'])}"]
    inter = {i["oven"]: i for i in m["interference"]}
    for o in m["per_oven"]:
        f = o.get("fit")
        i = inter.get(o["oven"], {})
        out.append(f"oven{o['oven'] + 1} acc {fmt(o['accuracy'])} bp {fmt(f and f['bp'])} wf {fmt(f and f['wf'])}"
                   f" dwf {fmt(i.get('d_wf'), 3)} dbp {fmt(i.get('d_bp'))}")
    return f"success {all_m['success_rate']:.3f} " + " | ".join(out)


def reproduction_line(m):
    fmt = lambda v: "na" if v is None else f"{v:.2f}"  # noqa: E731
    out = []
    for c in m["reproduction"]["contexts"]:
        r = [x[1] for x in c["ratio"]]
        o = c.get("observer") or {"best": "na", "wm": None, "wp": None}  # fitted at gain 1 only
        rng = f"{min(r):.2f}-{max(r):.2f}" if r else "na"
        out.append(f"prior{c['prior']} g{c['gain']:g} slope {fmt(c['slope'])} bias {fmt(c['bias'])}"
                   f" sqrtvar {fmt(c['sqrt_var'])} wf {fmt(c['weber'])} ratio {rng}"
                   f" best {o['best']} wm {fmt(o['wm'])} wp {fmt(o['wp'])}")
    return f"success {m['success_rate']:.3f} " + " | ".join(out)


# The reproduction study's set-ups: (label, the job's settings), in the committed order.
REPRODUCTION_SETUPS = [("default", ()), ("ddm-rate0.5", ("reproduction_rate=0.5",)), ("gains", ("env.gains=1,1.5",))]


def reproduction_main(sweep_file, root):
    models, seeds = listed(open(sweep_file).read(), "models"), [int(s) for s in listed(open(sweep_file).read(), "seeds")]
    found = {}
    for job_path, metrics_path in jobs(root):
        job = json.load(open(job_path))
        if job.get("task") != "Reproduction-v0":
            continue
        found[(tuple(sorted(job.get("sets") or [])), job["model"], int(job["seed"]))] = metrics_path
    missing = 0
    for label, sets in REPRODUCTION_SETUPS:
        for model in models:
            for seed in seeds:
                path = found.get((tuple(sorted(sets)), model, seed))
                if path is None:
                    missing += label != "ddm-rate0.5" or model == "ddm"
                    continue
                print(f"{label} {model} {seed} {reproduction_line(json.load(open(path)))}", flush=True)
    if missing:
        print(f"{missing} jobs of the study not finished under {root}", file=sys.stderr)


def heldout_line(m):
    out = []
    for c in m["reproduction"]["contexts"]:
        r = [round(x[1], 2) for x in c["ratio"]]
        out.append(f"  prior {c['prior']} slope {c['slope']:.2f} {r}")
    return f"succ {m['success_rate']:.2f} " + " ".join(out)


# The held-out priors' set-up labels.
HELDOUT_PRIORS = {"intermediate": "inter", "10-16,15-21": "custom"}

KINDS = {
    # kind: (task, the line's label of a variant, the line's measures)
    "multi-anchor": ("MultiAnchor-v0", lambda v: dict(v)["anchors"], anchor_line),
    "multi-oven": ("MultiOven-v0", lambda v: ",".join(f"{k}={x}" for k, x in v), oven_line),
    "reproduction-heldout": ("Reproduction-v0", lambda v: HELDOUT_PRIORS[dict(v)["priors"]], heldout_line),
}


def summaries(task, sweep_file, root):
    """`(setup, model, seed) -> activity.summary.json` of the sweep's finished, recorded jobs
    of `task`, and the sweep file's variants, models and seeds."""
    text = open(sweep_file).read()
    found = {}
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames.sort()
        if "job.json" not in filenames or "activity.summary.json" not in filenames:
            continue
        job = json.load(open(os.path.join(dirpath, "job.json")))
        env = job.get("env") or {}
        if job.get("task") != task or not isinstance(env, dict):
            continue
        key = (frozenset((k, text_of(v)) for k, v in env.items()), job["model"], int(job["seed"]))
        found[key] = os.path.join(dirpath, "activity.summary.json")
    models, seeds = listed(text, "models"), [int(s) for s in listed(text, "seeds")]
    setups = variants(text) if "[task_variants]" in text else [()]
    return found, setups, models, seeds


def categories_main(sweep_file, root):
    """Unit categories of each recorded population, model by model, seed by seed, TD by TD
    (the sweep's variants in order); readouts (value, rpe, drift) left out."""
    found, setups, models, seeds = summaries("FixedInterval-v0", sweep_file, root)
    missing = 0
    for model in models:
        for seed in seeds:
            for setup in setups:
                path = found.get((frozenset(setup), model, seed))
                if path is None:
                    missing += 1
                    continue
                td = dict(setup)["td"]
                for pop in json.load(open(path)):
                    if pop["population"] in ("value", "rpe", "drift"):
                        continue
                    for t in pop["by_td"]:
                        c = t["categories"]
                        counts = " ".join(f"{k} {v}" for k, v in c["counts"].items() if v) if c else t["undefined"]
                        print(f"{model} seed {seed} TD {td} {pop['population']}: {t['units']} units: {counts}")
    if missing:
        print(f"{missing} jobs of the sweep not finished under {root}", file=sys.stderr)


def speed_main(sweep_file, root):
    """KiNeT's speed after Set: one JSON line per run, population and prior, runs in the
    order of their names `<model>-s<seed>`."""
    found, setups, models, seeds = summaries("Reproduction-v0", sweep_file, root)
    runs = sorted(((f"{m}-s{s}", m, s) for m in models for s in seeds), key=lambda r: r[0])
    missing = 0
    for _, model, seed in runs:
        path = found.get((frozenset(setups[0]), model, seed))
        if path is None:
            missing += 1
            continue
        for p in json.load(open(path)):
            for c in p.get("production_speed", []):
                print(json.dumps({"model": model, "seed": seed, "population": p["population"], **c}))
    if missing:
        print(f"{missing} jobs of the sweep not finished under {root}", file=sys.stderr)


def main():
    if len(sys.argv) == 4 and sys.argv[1] == "reproduction":
        return reproduction_main(sys.argv[2], sys.argv[3])
    if len(sys.argv) == 4 and sys.argv[1] == "categories":
        return categories_main(sys.argv[2], sys.argv[3])
    if len(sys.argv) == 4 and sys.argv[1] == "reproduction-speed":
        return speed_main(sys.argv[2], sys.argv[3])
    if len(sys.argv) != 4 or sys.argv[1] not in KINDS:
        sys.exit(__doc__.split("\n\n")[1])
    task, label, measures = KINDS[sys.argv[1]]
    text = open(sys.argv[2]).read()
    setups = variants(text)
    models, seeds = listed(text, "models"), [int(s) for s in listed(text, "seeds")]
    found = {}
    for job_path, metrics_path in jobs(sys.argv[3]):
        job = json.load(open(job_path))
        env = job.get("env") or {}
        if job.get("task") != task or not isinstance(env, dict):
            continue
        found[(frozenset((k, text_of(v)) for k, v in env.items()), job["model"], int(job["seed"]))] = metrics_path
    missing = 0
    for setup in setups:
        for model in models:
            for seed in seeds:
                path = found.get((frozenset(setup), model, seed))
                if path is None:
                    missing += 1
                    continue
                name = label(setup)
                if sys.argv[1] == "reproduction-heldout":  # the run's name, as the first grid named it
                    print(f"{name} r-{name}-{model}-{seed} {measures(json.load(open(path)))}", flush=True)
                else:
                    print(f"{name} {model} {seed} {measures(json.load(open(path)))}", flush=True)
    if missing:
        print(f"{missing} jobs of the sweep not finished under {sys.argv[3]}", file=sys.stderr)


if __name__ == "__main__":
    main()
