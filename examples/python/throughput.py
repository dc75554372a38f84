"""Python-side env-steps/s of the Rust-backed envs and of the original Python env, in one
run (one core): uniformly random actions, episodes reset when they end.

    python examples/python/throughput.py --ref-dir ref --seconds 5

* original: the original ``TimeProductionBasic`` (FI, TD 12, max_timesteps 200), scalar;
* scalar: ``gymnasium.make("chronocooked/FixedInterval-v0")`` (codes), unwrapped and wrapped;
* vector: ``gymnasium.make_vec(..., num_envs=N, vectorization_mode="vector_entry_point")``
  (codes, next-step autoreset), actions drawn ahead in numpy.
"""

import argparse
import importlib.util
import json
import os
import random
import time

import gymnasium as gym
import numpy as np

import chronocooked  # noqa: F401  (registers the envs)


def timed(step_batch, steps_per_call, seconds):
    calls = 0
    t0 = time.perf_counter()
    while time.perf_counter() - t0 < seconds:
        step_batch()
        calls += 1
    secs = time.perf_counter() - t0
    return calls * steps_per_call / secs


def scalar(env, seconds):
    rng = random.Random(2)
    env.reset(seed=1)
    actions = [rng.randrange(6) for _ in range(10_000)]

    def batch():
        for a in actions:
            _, _, term, trunc, _ = env.step(a)
            if term or trunc:
                env.reset()

    return timed(batch, len(actions), seconds)


def vector(n, seconds, obs_mode="codes"):
    env = gym.make_vec("chronocooked/FixedInterval-v0", num_envs=n,
                       vectorization_mode="vector_entry_point", obs_mode=obs_mode)
    env.reset(seed=0)
    rng = np.random.default_rng(0)
    actions = [rng.integers(0, 6, n) for _ in range(256)]

    def batch():
        for a in actions:
            env.step(a)

    return timed(batch, n * len(actions), seconds)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ref-dir", default=None)
    ap.add_argument("--seconds", type=float, default=5.0)
    args = ap.parse_args()
    out = {}
    if args.ref_dir:
        spec = importlib.util.spec_from_file_location(
            "time_production_basic", os.path.join(args.ref_dir, "time_production_basic.py"))
        mod = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(mod)
        out["original_scalar"] = scalar(mod.TimeProductionBasic(oven_duration=12, max_timesteps=200),
                                        args.seconds)
    out["chronocooked_scalar_unwrapped"] = scalar(
        gym.make("chronocooked/FixedInterval-v0", max_timesteps=200).unwrapped, args.seconds)
    out["chronocooked_scalar_gym_make"] = scalar(
        gym.make("chronocooked/FixedInterval-v0", max_timesteps=200), args.seconds)
    for n in (16, 256):
        out[f"chronocooked_vector{n}_codes"] = vector(n, args.seconds)
    out["chronocooked_vector256_onehot"] = vector(256, args.seconds, "onehot")
    if "original_scalar" in out:
        base = out["original_scalar"]
        out["ratios_vs_original"] = {k: round(v / base, 1) for k, v in out.items()
                                     if k != "original_scalar" and isinstance(v, float)}
    print(json.dumps({k: (round(v) if isinstance(v, float) else v) for k, v in out.items()}, indent=1))


if __name__ == "__main__":
    main()
