"""Steps/s of the original Python Chronocooked env (baseline for BENCHMARKS.md).

The original implementation is not part of this repository. Point --ref-dir at a
folder holding its `time_production_basic.py` (class TimeProductionBasic), with
numpy and gymnasium installed:

    python3 bench/python_env_steps.py --ref-dir /path/to/rl_environments --seconds 5

It steps the FI task (TD=12, max_timesteps=200) with uniformly random actions and
resets when an episode ends, like `chronocooked bench env` does.
"""
import argparse
import importlib.util
import json
import random
import time


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ref-dir", required=True)
    ap.add_argument("--seconds", type=float, default=5.0)
    args = ap.parse_args()
    spec = importlib.util.spec_from_file_location(
        "time_production_basic", f"{args.ref_dir}/time_production_basic.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    env = mod.TimeProductionBasic(oven_duration=12, max_timesteps=200)
    rng = random.Random(2)
    env.reset(seed=1)
    steps = 0
    start = time.perf_counter()
    while time.perf_counter() - start < args.seconds:
        for _ in range(10_000):
            _, _, terminated, truncated, _ = env.step(rng.randrange(6))
            if terminated or truncated:
                env.reset()
        steps += 10_000
    secs = time.perf_counter() - start
    print(json.dumps({"task": "FixedInterval (python original)", "steps": steps,
                      "seconds": secs, "steps_per_sec": steps / secs}))


if __name__ == "__main__":
    main()
