"""Two timing agents written for the fingerprint tests, neither of them a lab model: a
noisy pacemaker-accumulator (drift-diffusion-like: one accumulator whose drift is set by
the learned interval, so its activity is a ramp that stretches with the interval) and an
oscillator bank (striatal-beat-frequency-like: oscillators of fixed frequencies whose
pattern at the learned interval is remembered and detected by coincidence).

Both walk the kitchen with the scripted navigation of ``policies.Grid``: fetch the onion,
put it in the oven, wait next to the oven, check it (interact) while their clock says the
soup is due, take the soup to the counter (bisection: the short or the long one, by their
clock at the ready cue). Per-trial clock noise comes from their own seeded generator.
"""

import numpy as np

from policies import INTERACT, WAIT, Grid, _agent

SHORT_COUNTER, LONG_COUNTER, ONION, OVEN = 4, 8, 3, 5


class _Walker:
    """Shared navigation and trial clock: ``t`` = the oven's timer (1 at the first step the
    oven is seen on)."""

    def __init__(self, task, params, seed):
        self.bisection = task == "Bisection-v0"
        self.td = params.get("td")
        self.short, self.long = params.get("short"), params.get("long")
        self.rng = np.random.default_rng(seed)
        self.grid = None

    def begin(self):
        """A new trial: the per-trial clock noise."""

    def respond(self, t):
        """Whether the agent checks the oven ``t`` steps after oven-on (fixed interval)."""
        raise NotImplementedError

    def choose_long(self, t):
        """Bisection: whether ``t`` steps (at the ready cue) are judged long."""
        raise NotImplementedError

    def activity(self, t):
        raise NotImplementedError

    def __call__(self, obs, state, episode_start):
        if self.grid is None or self.grid.obj.shape != obs.shape[:2]:
            self.grid = Grid(obs)
        g = self.grid
        if episode_start or state is None:
            self.begin()
            state = {"t": None, "long": None}
        a = _agent(obs)
        oven = tuple(np.argwhere(g.obj == OVEN)[0])
        oven_state = int(obs[oven][4])
        onion, soup = obs[a][2] == 1, obs[a][3] == 1
        if state["t"] is None and oven_state != 0:
            state["t"] = 1  # the oven's timer at the first step it is seen on
        elif state["t"] is not None and not soup:
            state["t"] += 1
        t = state["t"]
        oven_adj = g.adjacent(OVEN)
        if soup:
            code = LONG_COUNTER if state["long"] else SHORT_COUNTER
            action = g.go_interact(a, g.nearest(a, g.adjacent(code)))
        elif onion:
            action = g.go_interact(a, g.nearest(a, oven_adj))
        elif t is None:
            onion_adj = g.adjacent(ONION)
            best = min(onion_adj, key=lambda x: g.d(a, x) + min(g.d(x, y) for y in oven_adj))
            action = g.go_interact(a, best)
        else:
            post = g.nearest(a, oven_adj)
            if a != post:
                action = g.towards(a, post)
            elif self.bisection:
                if oven_state == 2:
                    state["long"] = self.choose_long(t)
                    action = INTERACT
                else:
                    action = WAIT
            else:
                action = INTERACT if self.respond(t) else WAIT
        return action, state, self.activity(-1 if t is None else t)


class Accumulator(_Walker):
    """Pacemaker-accumulator: per trial a pulse rate ``r ~ N(1, cv)``; the accumulator
    ``x(t) = r t / T`` reaches 1 at the learned interval ``T`` (fixed interval: TD;
    bisection: the geometric mean of the anchors, the criterion). Responding starts at
    ``x = 1`` and stops at ``x = 1.6`` (the peak procedure's start and stop). Activity: 8
    ramps ``x`` times gains 0.5…2 plus offsets."""

    def __init__(self, task, params, seed=0, cv=0.15):
        super().__init__(task, params, seed)
        self.cv = cv
        self.interval = np.sqrt(self.short * self.long) if self.bisection else float(self.td)
        self.gains = np.linspace(0.5, 2.0, 8)
        self.offsets = np.linspace(-0.2, 0.2, 8)

    def begin(self):
        self.rate = max(0.3, 1.0 + self.cv * self.rng.standard_normal())

    def x(self, t):
        return self.rate * max(t, 0) / self.interval

    def respond(self, t):
        return 1.0 <= self.x(t) < 1.6

    def choose_long(self, t):
        return self.x(t) > 1.0

    def activity(self, t):
        return (self.gains * self.x(t) + self.offsets).astype(np.float32)


class OscillatorBank(_Walker):
    """Striatal beat frequency (after Matell & Meck 2004): 64 cortical oscillators with
    fixed frequencies drawn once from 0.125–0.375 cycles per step (5–15 Hz at 25 ms per
    step), phase-reset at oven-on and sped or slowed together by a per-trial clock factor
    ``m = exp(0.05 ε)``. Memory: a remembered time ``T (1 + κ ε')``, ``κ = 0.15``, sampled
    per trial (the source of scalar timing). A coincidence detector with complex weights
    (the oscillators' phases at the remembered time) reads the match envelope
    ``|mean_i exp(2πi f_i (m t − T̃))|``, 1 at the remembered time. Fixed interval:
    responding starts when the envelope first exceeds 0.9 and stops at 2.2 × the start time
    (the lab's SBF has no stop rule of its own: it responds until its "overdue" category,
    about twice the remembered time); bisection: a criterion remembered at the anchors'
    geometric mean, "long" when its envelope passed 0.9 before the cue. Activity: the 64
    oscillators, ``cos(2π f_i m t)``."""

    def __init__(self, task, params, seed=0, kappa=0.15):
        super().__init__(task, params, seed)
        self.kappa = kappa
        # The same oscillators at every TD (one bank): units correspond across conditions.
        self.freqs = np.random.default_rng(2004).uniform(0.125, 0.375, 64)
        self.m = 1.0

    def remembered(self, interval):
        return interval * (1 + self.kappa * self.rng.standard_normal())

    def begin(self):
        self.m = float(np.exp(0.05 * self.rng.standard_normal()))
        self.start = None
        self.memory = self.remembered(
            np.sqrt(self.short * self.long) if self.bisection else self.td)

    def envelope(self, t):
        return float(abs(np.mean(np.exp(2j * np.pi * self.freqs * (self.m * t - self.memory)))))

    def respond(self, t):
        if self.start is None:
            if self.envelope(t) > 0.9:
                self.start = t
            return self.start is not None
        return t <= 2.2 * self.start

    def choose_long(self, t):
        # Did the criterion's detector fire before the cue?
        return any(self.envelope(tau) > 0.9 for tau in range(1, t + 1))

    def activity(self, t):
        return np.cos(2 * np.pi * self.freqs * self.m * max(t, 0)).astype(np.float32)


class TimeCellChain(Accumulator):
    """A chain of time cells on the accumulator's clock: 40 units with Gaussian fields at
    log-spaced delays from 0.1 to 3 × the learned interval, each as wide as a quarter of
    its delay (a scale-invariant sequence, after Howard et al. 2014). Behaviour: the
    accumulator's."""

    def __init__(self, task, params, seed=0, cv=0.15):
        super().__init__(task, params, seed, cv)
        self.delays = np.geomspace(0.1, 3.0, 40)

    def activity(self, t):
        x = self.x(t)
        return np.exp(-((x - self.delays) ** 2) / (2 * (0.25 * self.delays) ** 2)).astype(np.float32)


class Mixed:
    """An agent whose activity is seen through a fixed random orthogonal matrix (Haar, from
    a QR decomposition with the signs fixed; the same matrix in every condition)."""

    def __init__(self, agent, seed=11):
        self.agent = agent
        self.q = None
        self.seed = seed

    def __call__(self, obs, state, episode_start):
        action, state, activity = self.agent(obs, state, episode_start)
        if self.q is None:
            g = np.random.default_rng(self.seed).standard_normal((activity.size, activity.size))
            q, r = np.linalg.qr(g)
            self.q = q * np.sign(np.diag(r))
        return action, state, (self.q @ activity.astype(np.float64)).astype(np.float32)
