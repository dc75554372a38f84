"""Training env-steps/s of the Python baseline: Stable-Baselines3 PPO and sb3-contrib
RecurrentPPO on the original Python Fixed-Interval env (TD=12), one torch thread.

This is a stand-alone measurement script for BENCHMARKS.md. No Rust test or build
step uses it. It needs a Python environment with the packages pinned in
`bench/requirements-sb3.txt` and a folder holding the original implementation's
`time_production_basic.py` (class TimeProductionBasic), which is not part of this
repository:

    python3 -m venv .venv-sb3
    .venv-sb3/bin/pip install -r bench/requirements-sb3.txt
    .venv-sb3/bin/python bench/sb3_baseline.py --ref-dir /path/to/ref \
        --ppo-updates 5 --rppo-updates 3 [--rppo-lstm both] [--json]

`bench/run_baseline.sh` runs this script and then `chronocooked bench train` in one
go, so both sides are measured under the same machine conditions.

What it measures
----------------
For each model: one warm-up update (`learn(1000)`), then the wall time of
`learn(N * 1000, reset_num_timesteps=False)`, i.e. N further PPO updates of
1000 env steps each (rollout + 20 epochs of optimisation). It reports
env-steps/s = N * 1000 / wall seconds, seconds per update, and the split of that
time into rollout collection and optimisation (from a callback's rollout
start/end timestamps).

Configuration (the paper's SB3 setup)
-------------------------------------
* env: TimeProductionBasic(oven_duration=12, max_timesteps=200), observation
  Box(0, 20, (5, 3, 6), uint8) channel-last, Discrete(6); one copy, wrapped in
  Monitor inside a DummyVecEnv.
* features extractor (custom BaseFeaturesExtractor, features_dim 64): permute
  (5,3,6) channel-last to (6,5,3) float -> Conv2d 1x1 6->8, ReLU ->
  Conv2d 1x1 8->6 -> flatten (90) -> Linear 90->64, ReLU.
* policies are declared as "MlpPolicy" / "MlpLstmPolicy" with that extractor and
  normalize_images=False (the observation is not 0-255 image data; SB3 would not
  treat it as an image anyway since high=20 and it has 6 channels, so no
  VecTransposeImage and no /255 scaling happen). share_features_extractor=True
  (default), net_arch dict(pi=[64], vf=[64]), activation_fn default (Tanh).
* PPO: n_steps 1000, batch_size 64 (default), n_epochs 20, lr 3e-4, gamma 0.99,
  gae_lambda 0.95, clip_range 0.2, ent_coef 0, vf_coef 0.5, max_grad_norm 0.5.
* RecurrentPPO: same, batch_size 128 (its default), lstm_hidden_size 125,
  n_lstm_layers 1. Two LSTM layouts (--rppo-lstm, default "both"):
  - "default" (model rppo-lstm125): shared_lstm False, enable_critic_lstm True,
    the sb3-contrib defaults: separate actor and critic LSTMs (2 x LSTM125).
  - "shared" (model rppo-lstm125-shared): shared_lstm True,
    enable_critic_lstm False: one LSTM feeding both heads, the layout of
    chronocooked's `lstm125` ("LSTM core shared by actor and critic").
* device "cpu", torch.set_num_threads(1) (and set_num_interop_threads(1)).
"""
import argparse
import importlib.util
import json
import os
import platform
import sys
import time

# One thread everywhere, set before torch is imported.
for _var in ("OMP_NUM_THREADS", "MKL_NUM_THREADS", "OPENBLAS_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import gymnasium as gym  # noqa: E402
import numpy as np  # noqa: E402
import torch  # noqa: E402
import torch.nn as nn  # noqa: E402
import stable_baselines3  # noqa: E402
import sb3_contrib  # noqa: E402
from stable_baselines3 import PPO  # noqa: E402
from stable_baselines3.common.callbacks import BaseCallback  # noqa: E402
from stable_baselines3.common.monitor import Monitor  # noqa: E402
from stable_baselines3.common.torch_layers import BaseFeaturesExtractor  # noqa: E402
from stable_baselines3.common.vec_env import DummyVecEnv  # noqa: E402
from sb3_contrib import RecurrentPPO  # noqa: E402

STEPS_PER_UPDATE = 1000


class GridCnnExtractor(BaseFeaturesExtractor):
    """(B, 5, 3, 6) channel-last grid -> 1x1 conv trunk -> 64 features."""

    def __init__(self, observation_space: gym.spaces.Box, features_dim: int = 64):
        super().__init__(observation_space, features_dim)
        h, w, c = observation_space.shape
        self.cnn = nn.Sequential(
            nn.Conv2d(c, 8, kernel_size=1),
            nn.ReLU(),
            nn.Conv2d(8, c, kernel_size=1),
            nn.Flatten(),
        )
        self.linear = nn.Sequential(nn.Linear(c * h * w, features_dim), nn.ReLU())

    def forward(self, obs: torch.Tensor) -> torch.Tensor:
        x = obs.float().permute(0, 3, 1, 2)
        return self.linear(self.cnn(x))


class PhaseTimer(BaseCallback):
    """Records wall-clock timestamps of rollout start/end to split update time."""

    def __init__(self):
        super().__init__()
        self.starts = []
        self.ends = []

    def _on_rollout_start(self) -> None:
        self.starts.append(time.perf_counter())

    def _on_rollout_end(self) -> None:
        self.ends.append(time.perf_counter())

    def _on_step(self) -> bool:
        return True


def load_env_class(ref_dir):
    path = os.path.join(ref_dir, "time_production_basic.py")
    spec = importlib.util.spec_from_file_location("time_production_basic", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.TimeProductionBasic


def make_vec_env(env_cls):
    def _make():
        if env_cls is None:
            # The lab's Rust-backed env (the `chronocooked` Python package).
            import chronocooked  # noqa: F401  (registers the envs)
            return Monitor(gym.make("chronocooked/FixedInterval-v0", td=12, max_timesteps=200))
        return Monitor(env_cls(oven_duration=12, max_timesteps=200))

    return DummyVecEnv([_make])


COMMON = dict(
    n_steps=STEPS_PER_UPDATE,
    n_epochs=20,
    learning_rate=3e-4,
    gamma=0.99,
    gae_lambda=0.95,
    clip_range=0.2,
    ent_coef=0.0,
    vf_coef=0.5,
    max_grad_norm=0.5,
    device="cpu",
    verbose=0,
)

EXTRACTOR = dict(
    features_extractor_class=GridCnnExtractor,
    features_extractor_kwargs=dict(features_dim=64),
    net_arch=dict(pi=[64], vf=[64]),
    normalize_images=False,
)


def build(name, env, seed):
    if name == "ppo-cnn-mlp":
        return PPO("MlpPolicy", env, batch_size=64, policy_kwargs=dict(EXTRACTOR),
                   seed=seed, **COMMON)
    if name.startswith("rppo-lstm"):
        shared = name.endswith("-shared")
        size = int(name[len("rppo-lstm"):].removesuffix("-shared"))
        kwargs = dict(EXTRACTOR, lstm_hidden_size=size, n_lstm_layers=1,
                      shared_lstm=shared, enable_critic_lstm=not shared)
        return RecurrentPPO("MlpLstmPolicy", env, batch_size=128, policy_kwargs=kwargs,
                            seed=seed, **COMMON)
    raise ValueError(name)


def measure(name, env_cls, updates, seed):
    env = make_vec_env(env_cls)
    model = build(name, env, seed)
    n_params = sum(p.numel() for p in model.policy.parameters())
    # Warm-up: one full update (rollout + optimisation).
    t0 = time.perf_counter()
    model.learn(total_timesteps=STEPS_PER_UPDATE)
    warm_secs = time.perf_counter() - t0
    start_steps = model.num_timesteps
    cb = PhaseTimer()
    t0 = time.perf_counter()
    model.learn(total_timesteps=updates * STEPS_PER_UPDATE, callback=cb,
                reset_num_timesteps=False)
    t1 = time.perf_counter()
    secs = t1 - t0
    steps = model.num_timesteps - start_steps
    rollout = sum(e - s for s, e in zip(cb.starts, cb.ends))
    # Optimisation after rollout i ends at the next rollout start (or at learn's return).
    opt_ends = cb.starts[1:] + [t1]
    optimise = sum(o - e for e, o in zip(cb.ends, opt_ends))
    n_up = len(cb.ends)
    env.close()
    return {
        "model": name,
        "updates": n_up,
        "steps": steps,
        "seconds": secs,
        "env_steps_per_sec": steps / secs,
        "sec_per_update": secs / max(n_up, 1),
        "rollout_sec_per_update": rollout / max(n_up, 1),
        "optimise_sec_per_update": optimise / max(n_up, 1),
        "warmup_seconds": warm_secs,
        "n_params": n_params,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ref-dir", default="ref",
                    help="folder holding the original time_production_basic.py")
    ap.add_argument("--ppo-updates", type=int, default=5,
                    help="timed PPO updates (1000 steps each) after one warm-up update")
    ap.add_argument("--rppo-updates", type=int, default=3,
                    help="timed RecurrentPPO updates (1000 steps each) after one warm-up")
    ap.add_argument("--rppo-lstm", choices=["default", "shared", "both"], default="both",
                    help="RecurrentPPO LSTM layout: sb3-contrib default (separate actor "
                         "and critic LSTMs), shared (one LSTM), or both")
    ap.add_argument("--rppo-sizes", default="125",
                    help="comma-separated LSTM sizes for RecurrentPPO (e.g. 8,125,256)")
    ap.add_argument("--env", choices=["original", "chronocooked"], default="original",
                    help="original Python env (needs --ref-dir) or the lab's Rust-backed "
                         "chronocooked/FixedInterval-v0 (the `chronocooked` package)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--json", action="store_true", help="print JSON lines")
    args = ap.parse_args()

    torch.set_num_threads(1)
    try:
        torch.set_num_interop_threads(1)
    except RuntimeError:
        pass

    if args.env == "original":
        env_cls = load_env_class(args.ref_dir)
        probe = env_cls(oven_duration=12, max_timesteps=200)
    else:
        env_cls = None
        probe = make_vec_env(None).envs[0]
    info = {
        "python": platform.python_version(),
        "torch": torch.__version__,
        "stable_baselines3": stable_baselines3.__version__,
        "sb3_contrib": sb3_contrib.__version__,
        "gymnasium": gym.__version__,
        "numpy": np.__version__,
        "torch_threads": torch.get_num_threads(),
        "observation_space": str(probe.observation_space),
        "action_space": str(probe.action_space),
    }
    if args.json:
        print(json.dumps({"versions": info}), flush=True)
    else:
        print("# " + ", ".join(f"{k}={v}" for k, v in info.items()), flush=True)

    runs = [("ppo-cnn-mlp", args.ppo_updates)]
    for size in [int(x) for x in args.rppo_sizes.split(",") if x]:
        if args.rppo_lstm in ("default", "both"):
            runs.append((f"rppo-lstm{size}", args.rppo_updates))
        if args.rppo_lstm in ("shared", "both"):
            runs.append((f"rppo-lstm{size}-shared", args.rppo_updates))
    for name, updates in runs:
        if updates <= 0:
            continue
        r = measure(name, env_cls, updates, args.seed)
        r["task"] = ("FixedInterval TD=12 (python original, SB3)" if env_cls is not None
                     else "chronocooked/FixedInterval-v0 TD=12 (Rust-backed env, SB3)")
        if args.json:
            print(json.dumps(r), flush=True)
        else:
            print(f"SB3 {name:<20} {r['env_steps_per_sec']:8.1f} env-steps/s  "
                  f"({r['sec_per_update']:.3f} s/update: rollout "
                  f"{r['rollout_sec_per_update']:.3f} s, optimise "
                  f"{r['optimise_sec_per_update']:.3f} s; {r['updates']} updates, "
                  f"{r['steps']} steps in {r['seconds']:.2f} s; {r['n_params']} params)",
                  flush=True)


if __name__ == "__main__":
    sys.exit(main())
