"""The paper's protocol, lab vs SB3, in one run: env-steps/s, achieved GFLOP/s and percent
of this core's single-thread SGEMM rate for every model at sizes 8/125/256, and SB3 PPO /
sb3-contrib RecurrentPPO (shared LSTM, the paper's layout) on the lab's Rust-backed env.

    $SB3_VENV/bin/python bench/protocol_compare.py [--rounds 2] [--updates 3]

Runs from the repository root with the venv of `bench/requirements-sb3.txt` plus the
`chronocooked` Python package. Each round measures, one after the other: numpy's
single-thread SGEMM (2048², float32), `chronocooked bench train` (reference preset, FI
TD 12, one thread) for every model, then `bench/sb3_baseline.py --env chronocooked`.
Rounds alternate lab and baseline so that machine load hits both alike; the table gives
medians over rounds. Model FLOPs per env step = forward multiply–adds × 2 × (1 + 3 × 20
epochs) of one transition (convolutions, dense, core input and recurrent products,
heads; element-wise work not counted).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

for _var in ("OMP_NUM_THREADS", "MKL_NUM_THREADS", "OPENBLAS_NUM_THREADS"):
    os.environ[_var] = "1"
import numpy as np  # noqa: E402

SIZES = (8, 125, 256)
KINDS = {"lstm": 4, "gru": 3, "rnn": 1, "ctrnn": 1, "ctrnn-reservoir": 1}


def forward_flops(model):
    """FLOPs of one transition's forward pass (2 × multiply–adds)."""
    cells, ch, c1, c2, feat, head, actions = 15, 6, 8, 6, 64, 64, 6
    macs = cells * (ch * c1 + c1 * c2) + cells * c2 * feat
    latent = feat
    if model != "cnn-mlp":
        kind = model.rstrip("0123456789")
        h = int(model[len(kind):])
        gh = KINDS[kind] * h
        macs += feat * gh + h * gh
        latent = h
    macs += latent * 2 * head + head * actions + head
    return 2 * macs


def sgemm_gflops(n=2048, reps=5):
    a = np.random.default_rng(0).standard_normal((n, n), dtype=np.float32)
    b = a.T.copy()
    a @ b
    rates = []
    for _ in range(reps):
        t = time.perf_counter()
        a @ b
        rates.append(2 * n ** 3 / (time.perf_counter() - t) / 1e9)
    return statistics.median(rates)


def lab_rates(binary, models, updates):
    out = subprocess.run(
        [binary, "bench", "train", "--models", ",".join(models), "--updates", str(updates),
         "--set", "env.td=12"], capture_output=True, text=True, check=True).stdout
    rates = {}
    for line in out.splitlines():
        f = line.split()
        if len(f) > 5 and f[5] == "env-steps/s":
            rates[f[1]] = float(f[4])
    return rates


def sb3_rates(sizes, updates):
    cmd = [sys.executable, "-W", "ignore", "bench/sb3_baseline.py", "--env", "chronocooked",
           "--json", "--ppo-updates", str(updates), "--rppo-updates", str(updates),
           "--rppo-lstm", "shared", "--rppo-sizes", ",".join(map(str, sizes))]
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    rates = {}
    for line in out.splitlines():
        d = json.loads(line)
        if "model" in d:
            rates[d["model"]] = d["env_steps_per_sec"]
    return rates


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--chronocooked", default="./target/release/chronocooked")
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--updates", type=int, default=3, help="lab updates per model and round")
    ap.add_argument("--sb3-updates", type=int, default=2,
                    help="SB3 updates per model and round (after one warm-up)")
    ap.add_argument("--sb3-sizes", default="8,125,256")
    ap.add_argument("--models", default=",".join(
        ["cnn-mlp"] + [f"{k}{s}" for k in KINDS for s in SIZES]))
    args = ap.parse_args()
    models = args.models.split(",")
    sizes = [int(s) for s in args.sb3_sizes.split(",") if s]
    sgemm, lab, sb3 = [], {}, {}
    print(f"# {time.strftime('%Y-%m-%d %H:%M:%S UTC', time.gmtime())}, load {os.getloadavg()}",
          flush=True)
    for r in range(args.rounds):
        sgemm.append(sgemm_gflops())
        for k, v in lab_rates(args.chronocooked, models, args.updates).items():
            lab.setdefault(k, []).append(v)
        if sizes or args.sb3_updates > 0:
            for k, v in sb3_rates(sizes, args.sb3_updates).items():
                sb3.setdefault(k, []).append(v)
        sgemm.append(sgemm_gflops())
        print(f"# round {r + 1}: SGEMM {sgemm[-2]:.1f} / {sgemm[-1]:.1f} GFLOP/s, "
              f"load {os.getloadavg()}", flush=True)
    peak = statistics.median(sgemm)
    print(f"\nnumpy single-thread SGEMM (median of {len(sgemm)}): {peak:.1f} GFLOP/s\n")
    print("| model | lab env-steps/s | GFLOP/s | % of SGEMM | SB3 env-steps/s | lab ÷ SB3 |")
    print("|---|---:|---:|---:|---:|---:|")
    for m in models:
        if m not in lab:
            continue
        rate = statistics.median(lab[m])
        gf = rate * forward_flops(m) * (1 + 3 * 20) / 1e9
        base = "ppo-cnn-mlp" if m == "cnn-mlp" else (
            f"rppo-{m}-shared" if m.startswith("lstm") else None)
        s = statistics.median(sb3[base]) if base in sb3 else None
        sb3_txt = f"{s:,.0f}" if s else "–"
        ratio = f"{rate / s:.1f}×" if s else "–"
        print(f"| {m} | {rate:,.0f} | {gf:.1f} | {100 * gf / peak:.0f}% | {sb3_txt} | {ratio} |")
    print(f"\nraw: {json.dumps({'sgemm': sgemm, 'lab': lab, 'sb3': sb3})}")


if __name__ == "__main__":
    main()
