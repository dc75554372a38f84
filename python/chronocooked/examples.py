"""Example agents written from scratch in Python, to try the benchmark with and to copy as a
starting point for your own (tutorial 2, ``docs/tutorials/2-your-agent.md``).

* :class:`PacemakerAgent`: a pacemaker-accumulator. It walks to the onion, puts it in the
  oven, then counts its own noisy pulses and checks the oven when the count reaches the
  interval it was built for (fixed interval), or judges the cooking time short or long
  against a criterion count (bisection). Its activity is the count and Gaussian "time
  cells" tuned to counts 0, 2, 4, …
* :func:`make_pacemaker`: ``make_policy(task, params)`` for :func:`chronocooked.fingerprint`,
  one pacemaker per condition of the mechanisms protocol.

A policy is any callable ``policy(obs, state, episode_start) -> (action, state, activity)``
(observation ``uint8 [R, C, 6]``, action 0–5, activity ``float32 [units]`` or ``None``).
"""

from collections import deque

import numpy as np

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


def make_pacemaker(task, params):
    """``make_policy(task, params)`` for :func:`chronocooked.fingerprint`: one pacemaker
    agent per condition, built for its interval (bisection: the criterion between the
    anchors is their geometric mean, the bisection point of a scalar timer)."""
    if task == "Bisection-v0":
        return PacemakerAgent(criterion=(params["short"] * params["long"]) ** 0.5)
    return PacemakerAgent(params["td"])
