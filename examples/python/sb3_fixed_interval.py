"""SB3 PPO with the paper's CNN feature extractor on the fixed-interval task (TD 4),
on the Rust-backed env (`chronocooked/FixedInterval-v0`) or on the original Python env,
with the paper's hyperparameters (n_steps 1000, n_epochs 20, ent_coef 0, gamma 0.99, SB3
defaults otherwise; one env, one thread). Prints env-steps/s and, for the Rust-backed env,
the success rate of the lab's reference evaluation (chronocooked.evaluate).

    python examples/python/sb3_fixed_interval.py --env chronocooked --steps 200000 --out lab-out/sb3-fi4
    python examples/python/sb3_fixed_interval.py --env original --ref-dir ref --steps 50000

Needs: the chronocooked package, stable-baselines3, torch (bench/requirements-sb3.txt).
"""

import argparse
import importlib.util
import json
import os
import sys
import time

import gymnasium as gym
import numpy as np
import torch
from stable_baselines3 import PPO
from stable_baselines3.common.callbacks import BaseCallback
from stable_baselines3.common.torch_layers import BaseFeaturesExtractor



class PaperCNN(BaseFeaturesExtractor):
    """The paper's feature extractor: (H, W, 6) -> (6, H, W) -> 1x1 conv 6->8 -> ReLU ->
    1x1 conv 8->6 -> flatten -> linear -> 64 -> ReLU (obs fed as raw integer codes)."""

    def __init__(self, observation_space, features_dim=64, n_channels=6):
        super().__init__(observation_space, features_dim)
        h, w, _ = observation_space.shape
        self.convs = torch.nn.Sequential(
            torch.nn.Conv2d(n_channels, 8, 1), torch.nn.ReLU(), torch.nn.Conv2d(8, n_channels, 1),
            torch.nn.Flatten())
        self.linear = torch.nn.Sequential(torch.nn.Linear(n_channels * h * w, features_dim),
                                          torch.nn.ReLU())

    def forward(self, obs):
        return self.linear(self.convs(obs.permute(0, 3, 1, 2)))


class Progress(BaseCallback):
    def __init__(self):
        super().__init__()
        self.episodes = []

    def _on_step(self):
        for info in self.locals.get("infos", []):
            if "episode" in info:
                self.episodes.append(info["episode"]["r"])
        return True


def make_env(kind, ref_dir, td):
    if kind == "chronocooked":
        import chronocooked  # noqa: F401  (registers the envs)
        return gym.make("chronocooked/FixedInterval-v0", td=td, max_timesteps=200)
    spec = importlib.util.spec_from_file_location(
        "time_production_basic", os.path.join(ref_dir, "time_production_basic.py"))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.TimeProductionBasic(oven_duration=td, max_timesteps=200)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--env", choices=["chronocooked", "original"], default="chronocooked")
    ap.add_argument("--ref-dir", default="ref", help="folder with the original time_production_basic.py")
    ap.add_argument("--td", type=int, default=4)
    ap.add_argument("--steps", type=int, default=200_000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out", default=None, help="evaluation folder (chronocooked env only)")
    args = ap.parse_args()
    torch.set_num_threads(1)
    env = make_env(args.env, args.ref_dir, args.td)
    model = PPO("MlpPolicy", env, n_steps=1000, n_epochs=20, ent_coef=0.0, gamma=0.99,
                seed=args.seed, device="cpu", verbose=0,
                policy_kwargs=dict(features_extractor_class=PaperCNN,
                                   features_extractor_kwargs=dict(features_dim=64),
                                   net_arch=dict(pi=[64], vf=[64])))
    cb = Progress()
    t0 = time.perf_counter()
    model.learn(total_timesteps=args.steps, callback=cb)
    secs = time.perf_counter() - t0
    last = cb.episodes[-200:]
    result = {"env": args.env, "td": args.td, "steps": args.steps, "seconds": round(secs, 1),
              "env_steps_per_sec": round(args.steps / secs, 1),
              "training_success_last_200_episodes": float(np.mean(np.array(last) >= 1)) if last else None}
    if args.env == "chronocooked":
        import chronocooked
        out = args.out or f"lab-out/sb3-fi{args.td}"
        s = chronocooked.evaluate(chronocooked.sb3.policy(model, record=False), "FixedInterval-v0", out, name="sb3-ppo-cnn",
                                  td=args.td, max_timesteps=200)
        _, conditions = chronocooked.load_eval(out)
        fi = conditions[conditions["kind"] == "fi"]
        result.update({"eval": out, "eval_success_all_conditions": s["success_rate"],
                       "eval_success_fi": float(fi["success_rate"].iloc[0])})
    print(json.dumps(result))


if __name__ == "__main__":
    main()
