#!/usr/bin/env python3
"""scipy's `curve_fit` on every curve a paper analysis fits (the notebook's psychometric
fit: logistic, p0 = [AM, 1], Levenberg-Marquardt, no bounds, failure -> step fallback,
BP outside the probes -> failed), in the order of `analysis/examples/lm_compare.rs`.

    python3 scripts/lsq-scipy-reference.py results/paper-core/analysis.json OUT.json

Needs numpy and scipy (not a project dependency: used to measure paper/lsq.rs)."""
import json
import sys
import warnings

import numpy as np
from scipy.optimize import curve_fit

warnings.simplefilter("ignore")


def logistic(x, x0, k):
    return 1.0 / (1.0 + np.exp(-(x - x0) / k))


def step_fallback(p, short, long):
    """The notebook's fallback: step-like when mean P over the first S entries <= 0.2 and
    from entry L on >= 0.8; quartile points from 0-based list positions."""
    p = np.asarray(p, float)
    if len(p) <= long or p[:short].mean() > 0.2 or p[long:].mean() < 0.8:
        return None

    def point(q):
        above, below = np.nonzero(p >= q)[0], np.nonzero(p <= q)[0]
        return None if len(above) == 0 or len(below) == 0 else 0.5 * (above[0] + below[-1])

    bp, q3, q1 = point(0.5), point(0.75), point(0.25)
    if bp is None or q3 is None or q1 is None:
        return None
    return {"how": "step_fallback", "bp": bp, "k": 0.5 * (q3 - q1) / np.log(3)}


def fit(p_long, short, long):
    pairs = [(d, y) for d, y in zip(range(1, long + 5), p_long) if y is not None]
    if len(pairs) < 2:
        return {"how": "failed"}
    d, y = (np.array(v, float) for v in zip(*pairs))
    try:
        (x0, k), _ = curve_fit(logistic, d, y, p0=[0.5 * (short + long), 1.0])
    except RuntimeError:
        return step_fallback(y, short, long) or {"how": "failed"}
    if not d.min() < x0 < d.max():
        return {"how": "failed"}
    return {"how": "fit", "bp": float(x0), "k": float(k)}


def main():
    analysis = json.load(open(sys.argv[1]))
    out = []
    for model in analysis["bisection"]:
        for cell in model["cells"]:
            curves = [r["p_long"] for r in cell["runs"]] + [cell["curve"]]
            out += [fit(p, cell["short"], cell["long"]) for p in curves]
    json.dump(out, open(sys.argv[2], "w"))
    print(f"{len(out)} curves fitted")


if __name__ == "__main__":
    main()
