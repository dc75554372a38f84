#!/usr/bin/env python3
"""The best a timing agent with scalar clock noise can do on Reproduction-v0's reward.

An agent measures ts with a clock whose speed is a per-trial log-normal factor (SD `sigma`
of its log, the time cells' `clock_noise`), restarts the clock at Set with a fresh factor,
and responds when the production clock reads c(m). Its production is tp = round(c / k),
k the production trial's factor. The reward of a response is max(0, 1 - |tp - ts| / w),
w = tolerance * ts + tolerance_steps, discounted by gamma^tp (the TD learner's discount).
The ideal agent picks, for every measurement m, the c that maximises the expected
discounted reward under the posterior of ts given m (a discrete uniform prior). Prints
the mean tp/ts at each ts of each prior: what "regression to the mean" this noise and this
reward imply, against which the learned agents are compared (RESULTS.md, "The 0.8-1.2
criterion").

    python3 scripts/reproduction-ideal-observer.py [--sigma 0.15] [--gamma 0.97]
"""
import argparse

import numpy as np


def ideal_ratios(lo, hi, sigma, gamma, tolerance, tolerance_steps):
    ts_values = np.arange(lo, hi + 1)
    m_grid = np.linspace(np.log(lo) - 4 * sigma, np.log(hi) + 4 * sigma, 400)
    c_grid = np.linspace(lo * 0.5, hi * 1.5, 600)
    z = np.linspace(-4, 4, 41)
    z_weights = np.exp(-z**2 / 2)
    z_weights /= z_weights.sum()
    speed = np.exp(sigma * z)
    # Expected discounted reward of reading c, for each ts: [ts, c].
    reward = np.zeros((len(ts_values), len(c_grid)))
    for i, ts in enumerate(ts_values):
        tp = np.maximum(1, np.round(c_grid[:, None] / speed[None, :]))
        w = tolerance * ts + tolerance_steps
        r = np.maximum(0, 1 - np.abs(tp - ts) / w) * gamma**tp
        reward[i] = r @ z_weights
    # Posterior of ts given the log measurement m, and the best c for each m.
    likelihood = np.exp(-((m_grid[:, None] - np.log(ts_values)[None, :]) ** 2) / (2 * sigma**2))
    posterior = likelihood / likelihood.sum(1, keepdims=True)
    best_c = c_grid[np.argmax(posterior @ reward, axis=1)]
    ratios = []
    for ts in ts_values:
        p_m = np.exp(-((m_grid - np.log(ts)) ** 2) / (2 * sigma**2))
        p_m /= p_m.sum()
        tp = np.maximum(1, np.round(best_c[:, None] / speed[None, :])) @ z_weights
        ratios.append(float(p_m @ tp) / ts)
    return ratios


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sigma", type=float, default=0.15, help="clock noise (SD of log speed)")
    ap.add_argument("--gamma", type=float, default=0.97, help="discount per step")
    ap.add_argument("--tolerance", type=float, default=0.2)
    ap.add_argument("--tolerance-steps", type=float, default=1.0)
    args = ap.parse_args()
    if not args.sigma > 0:
        ap.error("--sigma must be > 0 (a noise-free clock reproduces every ts exactly)")
    for lo, hi in [(8, 14), (11, 17), (14, 20), (9, 15), (10, 16), (15, 21)]:
        r = ideal_ratios(lo, hi, args.sigma, args.gamma, args.tolerance, args.tolerance_steps)
        print(f"prior {lo}-{hi}: tp/ts " + " ".join(f"{x:.2f}" for x in r))


if __name__ == "__main__":
    main()
