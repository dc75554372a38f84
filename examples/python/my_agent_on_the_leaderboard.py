"""Your agent on the benchmark: evaluate any Python policy on fixed interval (TD 12), place
it on the leaderboard next to the committed paper-core baselines, and compare its activity
with a trained LSTM125 from the zoo.

    python examples/python/my_agent_on_the_leaderboard.py [OUT]     # default: lab-out/my-agent

Run from the repository (the baselines are results/paper-core; the zoo agent is compiled
into the package). Writes OUT/eval/mine, OUT/eval/lstm125, OUT/report/ and prints one
line per step; under a minute on 2 cores.

The agent here is a pacemaker-accumulator written from scratch: it walks to the onion, puts
it in the oven, then counts its own noisy pulses and checks the oven when the count reaches
the interval it was built for. Its activity is eight units: the accumulated count and
seven Gaussian "time cells" tuned to counts 0, 2, …, 12.
"""

import sys
from collections import deque
from pathlib import Path

import numpy as np

import chronocooked

WAIT, DOWN, UP, RIGHT, LEFT, INTERACT = range(6)
STEPS = {DOWN: (1, 0), UP: (-1, 0), RIGHT: (0, 1), LEFT: (0, -1)}
ONION, DELIVERY, OVEN, LONG_COUNTER = 3, 4, 5, 8


class PacemakerAgent:
    """Observations: reference codes ``uint8 [R, C, 6]`` (ch0 objects, ch1 agent, ch2 onion
    carried, ch3 soup carried, ch4 oven 0 off / 1 on / 2 ready — bisection's cue).
    Activity: ``float32 [1 + time cells]``: the count and Gaussian time cells every 2 counts."""

    def __init__(self, td=None, rate_sd=0.08, seed=0, criterion=None):
        """``td``: the fixed interval it checks at (steps); or, for bisection, ``criterion``:
        the count above which a duration is "long" (takes the soup to the long counter)."""
        if (td is None) == (criterion is None):
            raise ValueError("give td (fixed interval) or criterion (bisection)")
        self.td, self.criterion, self.rate_sd = td, criterion, rate_sd
        self.rng = np.random.default_rng(seed)
        self.centres = np.arange(0, (td or criterion) + 1, 2, dtype=np.float32)
        self.long = False

    def __call__(self, obs, state, episode_start):
        if episode_start:
            self.count, self.rate = 0.0, max(0.5, 1 + self.rate_sd * self.rng.standard_normal())
            self.long = False
        me = tuple(int(x) for x in np.argwhere(obs[:, :, 1] == 1)[0])
        oven = tuple(int(x) for x in np.argwhere(obs[:, :, 0] == OVEN)[0])
        oven_on = obs[oven][4] > 0
        if obs[:, :, 3].any():
            action = self.go_and_interact(obs, me, LONG_COUNTER if self.long else DELIVERY)
        elif obs[:, :, 2].any():
            action = self.go_and_interact(obs, me, OVEN)
        elif oven_on and self.criterion is not None:
            # Bisection: count until the ready cue, then judge the duration and take the soup.
            ready = obs[oven][4] == 2
            if not ready:
                self.count += self.rate
            self.long = self.count > self.criterion
            near = self.go_and_interact(obs, me, OVEN)
            action = near if near != INTERACT or ready else WAIT
        elif oven_on:
            self.count += self.rate  # one noisy pulse per step while the oven is on
            near = self.go_and_interact(obs, me, OVEN)
            action = near if near != INTERACT or self.count >= self.td else WAIT
        else:
            action = self.go_and_interact(obs, me, ONION)
        activity = np.concatenate((
            [self.count],
            np.exp(-0.5 * ((self.count - self.centres) / 1.5) ** 2),
        )).astype(np.float32)
        return action, state, activity

    @staticmethod
    def go_and_interact(obs, me, code):
        """Interact when next to the object ``code``, else step along a shortest path."""
        free = obs[:, :, 0] == 0
        rows, cols = free.shape

        def touches(cell):
            return any(
                0 <= cell[0] + dr < rows and 0 <= cell[1] + dc < cols
                and obs[cell[0] + dr, cell[1] + dc, 0] == code
                for dr, dc in STEPS.values()
            )

        if touches(me):
            return INTERACT
        first = {me: None}
        queue = deque([me])
        while queue:
            cell = queue.popleft()
            for action, (dr, dc) in STEPS.items():
                nxt = (cell[0] + dr, cell[1] + dc)
                if 0 <= nxt[0] < rows and 0 <= nxt[1] < cols and free[nxt] and nxt not in first:
                    first[nxt] = first[cell] if first[cell] is not None else action
                    if touches(nxt):
                        return first[nxt]
                    queue.append(nxt)
        return WAIT


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
