#!/usr/bin/env python3
"""The table of the multi-anchor timing study's lines (results/extensions): per
anchor set and model, the anchor accuracy over seeds, each boundary's mean BP with the
pair's GM and AM, in how many single runs the GM lies inside the run's own 95% interval of
the boundary, and in how many the model's rule's prediction does (over every boundary of
every seed).

SBF's and the time cells' predictions, given PREDICTIONS (the output of `cargo run --release
--example predicted_boundaries -- RUN_DIR …`: each run's own
timer — its learned anchor memories, clock noise and decision rule, without the task —
judging 2,000 trials per probe, then the lab's fit; `analysis::behaviour::predicted`), are
those simulated boundaries; without it, the GM of the anchors (their ratio rule's criterion
between remembered anchors). For drift-diffusion it is where the lab's logistic
fit over the pair's probes puts the 50% point of the ratio rule on its two noisy
accumulators and memories: P(long | t) as `models::timing::judgment::ddm_judgment_p_long`
integrates it (x ~ N(a t, m² a t) per accumulator, a = exp(κ ε)/anchor the trial's drift,
z 1, diffusion m 0.15, memory κ 0.2, "long" iff x_S·x_L ≥ 1), then a
binomial maximum-likelihood logistic in t over the probes a_i … a_(i+1), as
`analysis::behaviour::psychometric::fit_logistic` fits the measured curve.

    python3 scripts/multi-anchor-timing-table.py LINES [PREDICTIONS] > summary.md

LINES from `scripts/timing-study-lines.py multi-anchor` (the sweep `sweeps/timing-multi-anchor.toml`);
PREDICTIONS from `cargo run --release --example predicted_boundaries -- SWEEP_OUT/MultiAnchor-v0/
{sbf,timecells-*}~*/seed*/run` (run folders of the sweep, or of the older grid's `runs/`).
"""
import math
import os
import re
import sys
from collections import OrderedDict

DDM_NOISE = 0.15  # models::timing::zoo::DDM_NOISE
DDM_MEMORY_NOISE = 0.2  # models::timing::zoo::DDM_MEMORY_NOISE


def phi(x):
    return 0.5 * (1.0 + math.erf(x / math.sqrt(2.0)))


def product_at_least(mu_s, sd_s, mu_l, sd_l, k, n=200):
    """P(x_S x_L >= k), x ~ independent Gaussians (Simpson over x_S, as the Rust integral)."""
    lo, hi = max(0.0, mu_s - 10 * sd_s), mu_s + 10 * sd_s
    h = (hi - lo) / n

    def f(x):
        if x <= 0:
            return 0.0
        dens = math.exp(-0.5 * ((x - mu_s) / sd_s) ** 2) / (sd_s * math.sqrt(2 * math.pi))
        return dens * (1.0 - phi((k / x - mu_l) / sd_l))

    return (f(lo) + f(hi) + sum(f(lo + i * h) * (4 if i % 2 else 2) for i in range(1, n))) * h / 3


def memory_factors(kappa, points):
    """(exp(kappa e), weight) over e in +-5 SD, midpoint rule, normalised."""
    width = 10.0 / points
    raw = [(math.exp(kappa * e), math.exp(-0.5 * e * e))
           for e in (-5.0 + (i + 0.5) * width for i in range(points))]
    total = sum(w for _, w in raw)
    return [(f, w / total) for f, w in raw]


def ddm_p_long(t, s, l, m=DDM_NOISE, kappa=DDM_MEMORY_NOISE, points=20):
    """P(x_S x_L >= 1) after t steps, averaged over the two drifts' memory factors."""
    factors = memory_factors(kappa, points)
    p = 0.0
    for f_s, w_s in factors:
        a_s = f_s / s
        for f_l, w_l in factors:
            a_l = f_l / l
            p += w_s * w_l * product_at_least(
                a_s * t, m * math.sqrt(a_s * t), a_l * t, m * math.sqrt(a_l * t), 1.0)
    return min(max(p, 0.0), 1.0)


def logistic_bp(ts, ps):
    """Binomial ML logistic p = 1/(1 + exp(-(a + b t))) with equal counts (Newton with step
    halving, as the lab's fit): BP = -a/b."""
    def sig(x):
        return 1.0 / (1.0 + math.exp(-x)) if x >= 0 else math.exp(x) / (1.0 + math.exp(x))

    def loglik(a, b):
        total = 0.0
        for t, p in zip(ts, ps):
            q = min(max(sig(a + b * t), 1e-300), 1 - 1e-16)
            total += p * math.log(q) + (1 - p) * math.log(1 - q)
        return total

    b = 4.0 / (ts[-1] - ts[0])
    a = -b * sum(ts) / len(ts)
    for _ in range(200):
        g0 = g1 = h00 = h01 = h11 = 0.0
        for t, p in zip(ts, ps):
            q = sig(a + b * t)
            w = q * (1 - q)
            g0 += p - q
            g1 += (p - q) * t
            h00 += w
            h01 += w * t
            h11 += w * t * t
        det = h00 * h11 - h01 * h01
        da, db = (h11 * g0 - h01 * g1) / det, (h00 * g1 - h01 * g0) / det
        step, base = 1.0, loglik(a, b)
        while step > 1e-8 and loglik(a + step * da, b + step * db) < base:
            step /= 2
        a, b = a + step * da, b + step * db
        if abs(step * da) + abs(step * db) < 1e-12:
            break
    return -a / b


def run_key(path):
    """`SET-MODEL-SEED` of a run folder: a sweep job's run (`…/MODEL~env.anchors-4_8_16/
    seedN/run`) or the older grid's `runs/SET-MODEL-SEED`."""
    path = path.rstrip("/")
    if os.path.basename(path) != "run":
        return os.path.basename(path)
    job = os.path.dirname(path)
    seed = os.path.basename(job)[len("seed"):]
    model, _, variant = os.path.basename(os.path.dirname(job)).partition("~env.anchors-")
    return f"{variant.replace('_', ',')}-{model}-{seed}"


# "<run dir> bp1 bp2 …" per run (examples/predicted_boundaries.rs), keyed by the run's name.
SIMULATED = {}
if len(sys.argv) > 2:
    for line in open(sys.argv[2]):
        fields = line.split()
        if fields:
            SIMULATED[run_key(fields[0])] = [float(x) for x in fields[1:]]


_ddm_cache = {}


def ddm_prediction(lo, hi):
    if (lo, hi) not in _ddm_cache:
        ts = list(range(lo, hi + 1))
        _ddm_cache[(lo, hi)] = logistic_bp(ts, [ddm_p_long(t, lo, hi) for t in ts])
    return _ddm_cache[(lo, hi)]

cells = OrderedDict()
for line in open(sys.argv[1]):
    parts = line.split(" ", 5)
    anchors, model, seed, acc = parts[0], parts[1], parts[2], float(parts[4])
    fits = parts[5].strip().split(" | ") if len(parts) > 5 else []
    cell = cells.setdefault(
        (anchors, model), {"acc": [], "bounds": {}, "inside": 0, "rule_inside": 0, "fits": 0})
    values = [int(a) for a in anchors.split(",")]
    cell["acc"].append(acc)
    for k, f in enumerate(fits):
        m = re.match(r"([\d.]+)\[([\d.]+),([\d.]+)\]gm([\d.]+)([* ])am([\d.]+)", f)
        b = cell["bounds"].setdefault(k, {"bp": [], "gm": None, "am": None})
        if not m:
            continue
        bp, ci_lo, ci_hi = float(m[1]), float(m[2]), float(m[3])
        gm, star, am = float(m[4]), m[5], float(m[6])
        if model == "ddm":
            rule = ddm_prediction(values[k], values[k + 1])
        else:
            simulated = SIMULATED.get(f"{anchors}-{model}-{seed}", [])
            rule = simulated[k] if k < len(simulated) else None
        b["bp"].append(bp)
        b["gm"], b["am"] = gm, am
        if rule is not None:
            b.setdefault("rules", []).append(rule)
        cell["fits"] += 1
        cell["inside"] += star == "*"
        cell["rule_inside"] += (ci_lo <= rule <= ci_hi) if rule is not None else star == "*"

print("| anchors | model | anchor accuracy: mean (min–max), seeds | each boundary: mean BP over seeds (GM / AM; its rule's prediction, mean over seeds, where computed) | GM inside the run's 95% interval | rule's prediction inside |")
print("|---|---|---|---|---|---|")
for (anchors, model), c in cells.items():
    acc = c["acc"]
    bounds = []
    for k in sorted(c["bounds"]):
        b = c["bounds"][k]
        if not b["bp"]:
            bounds.append("no fit")
            continue
        note = "" if len(b["bp"]) == len(acc) else f" [{len(b['bp'])} fits]"
        rules = b.get("rules")
        pred = f"; {sum(rules) / len(rules):.2f}" if rules else ""
        bounds.append(
            f"{sum(b['bp']) / len(b['bp']):.2f} ({b['gm']:.2f} / {b['am']:.1f}{pred}){note}")
    print(f"| {anchors} | {model} | {sum(acc) / len(acc):.3f} ({min(acc):.3f}–{max(acc):.3f}) "
          f"| {'; '.join(bounds)} | {c['inside']} of {c['fits']} "
          f"| {c['rule_inside']} of {c['fits']} |")
