"""Your agent on the benchmark: evaluate any Python policy on fixed interval (TD 12), place
it on the leaderboard next to the committed paper-core baselines, and compare its activity
with a trained LSTM125 from the zoo.

    python examples/python/my_agent_on_the_leaderboard.py [OUT]     # default: lab-out/my-agent

Run from the repository (the baselines are results/paper-core; the zoo agent is compiled
into the package). Writes OUT/eval/mine, OUT/eval/lstm125, OUT/report/ and prints one
line per step; under a minute on 2 cores.

The agent is the package's example pacemaker-accumulator (``chronocooked.examples``,
written from scratch; copy it as a starting point): it walks to the onion, puts
it in the oven, then counts its own noisy pulses and checks the oven when the count reaches
the interval it was built for. Its activity is eight units: the accumulated count and
seven Gaussian "time cells" tuned to counts 0, 2, …, 12.
"""

import sys
from pathlib import Path

import numpy as np

import chronocooked
from chronocooked.examples import PacemakerAgent


def time_decoding_r2(eval_dir, td, ridge=1.0):
    """Cross-validated R² of a linear (ridge) read-out of the time since oven-on (0 … TD-1
    steps) from the oven-on-aligned activity ``[trials, time, units]`` of an evaluation:
    fitted on the even trials, scored on the odd ones."""
    arrays, _ = chronocooked.load_activity(eval_dir)
    cube = arrays["aligned"][:, :td, :].astype(float)
    trials, steps, units = cube.shape
    t = np.arange(steps, dtype=float)

    def design(part):
        x = part.reshape(-1, units)
        return np.concatenate([x, np.ones((len(x), 1))], axis=1), np.tile(t, len(part))

    (xa, ta), (xb, tb) = design(cube[0::2]), design(cube[1::2])
    coef = np.linalg.solve(xa.T @ xa + ridge * np.eye(units + 1), xa.T @ ta)
    return 1 - np.sum((xb @ coef - tb) ** 2) / np.sum((tb - tb.mean()) ** 2)


def main(out):
    out = Path(out)
    td = 12
    # 1. Evaluate your agent with the lab's reference protocol (every start cell; FI + peak
    #    probes) — the same folder `chronocooked eval` writes.
    chronocooked.evaluate(PacemakerAgent(td), "FixedInterval-v0", out / "eval" / "mine",
                          td=td, name="my-pacemaker")
    # 2. The zoo's trained LSTM125 (paper-core protocol, seed 4) on the same protocol.
    lstm = chronocooked.zoo.load("lstm125/FixedInterval-v0")
    chronocooked.evaluate(lstm, "FixedInterval-v0", out / "eval" / "lstm125", td=td,
                          name="zoo-lstm125")
    # 3. The leaderboard: both agents next to the committed baselines (results/paper-core).
    files = chronocooked.report([out / "eval" / "mine", out / "eval" / "lstm125"], out / "report")
    rows = [line.split(",") for line in (out / "report" / "report.csv").read_text().splitlines()]
    col = {name: i for i, name in enumerate(rows[0])}
    for r in rows[1:]:
        print(f"{r[0]:<34} runs {r[col['runs']]:>3}  FI success {float(r[col['fi_success']]):.2f}"
              f"  first check / TD {float(r[col['foc_over_td']]):.2f}")
    print("leaderboard:", files[0])
    # 4. Activity: how well does each population encode elapsed time after oven-on?
    for name in ("mine", "lstm125"):
        print(f"R² {name}: {time_decoding_r2(out / 'eval' / name, td):.3f}  (time since oven-on from activity)")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "lab-out/my-agent")
