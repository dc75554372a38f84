"""Python policies for the tests: the lab's scripted oracle re-written as a closed-loop
Python policy that sees only the codes observation (plus the task parameters it was
"trained" with) and counts steps itself.

Codes observation ``[R, C, 6]``: ch0 object code (3 onion, 4 delivery / short counter,
5 oven, 8 long counter), ch1 agent, ch2 carrying onion, ch3 carrying soup, ch4 oven
state (0 off, 1 on, 2 ready).
"""

from collections import deque

import numpy as np

WAIT, DOWN, UP, RIGHT, LEFT, INTERACT = range(6)
MOVES = [(DOWN, (1, 0)), (UP, (-1, 0)), (RIGHT, (0, 1)), (LEFT, (0, -1))]


class Grid:
    """Free cells, object neighbours and all-pairs shortest paths of one layout."""

    def __init__(self, obs):
        self.rows, self.cols = obs.shape[:2]
        self.obj = obs[:, :, 0].copy()
        self.cells = [(r, c) for r in range(self.rows) for c in range(self.cols)]
        self.free = [x for x in self.cells if self.obj[x] == 0]
        self.dist = {x: self._bfs(x) for x in self.free}

    def move(self, cell, delta):
        r, c = cell[0] + delta[0], cell[1] + delta[1]
        if 0 <= r < self.rows and 0 <= c < self.cols and self.obj[r, c] == 0:
            return (r, c)
        return cell

    def _bfs(self, src):
        d = {src: 0}
        q = deque([src])
        while q:
            x = q.popleft()
            for _, delta in MOVES:
                y = self.move(x, delta)
                if y not in d:
                    d[y] = d[x] + 1
                    q.append(y)
        return d

    def d(self, a, b):
        return self.dist[a].get(b, 10**6)

    def adjacent(self, code):
        """Free cells (row-major) touching an object with code ``code``."""
        out = []
        for x in self.free:
            for _, delta in MOVES:
                r, c = x[0] + delta[0], x[1] + delta[1]
                if 0 <= r < self.rows and 0 <= c < self.cols and self.obj[r, c] == code:
                    out.append(x)
                    break
        return out

    def nearest(self, a, cells):
        return min(cells, key=lambda c: self.d(a, c))

    def towards(self, a, b):
        if a == b:
            return WAIT
        here = self.d(a, b)
        for act, delta in MOVES:
            n = self.move(a, delta)
            if n != a and self.d(n, b) < here:
                return act
        return WAIT

    def go_interact(self, a, b):
        return INTERACT if a == b else self.towards(a, b)


def _agent(obs):
    r, c = np.argwhere(obs[:, :, 1] == 1)[0]
    return (int(r), int(c))


class TimingOracle:
    """Optimal closed-loop policy for fixed interval / peak interval (``td`` known, the
    oven timer counted from the onion-in step) and bisection (``short``/``long`` known,
    waits for the ready cue and classifies the counted duration against the geometric
    mean). ``__call__(obs, state, episode_start) -> (action, state)``."""

    def __init__(self, td=None, short=None, long=None, activity=False):
        self.td, self.short, self.long = td, short, long
        self.activity = activity
        self.grid = None

    def __call__(self, obs, state, episode_start):
        if self.grid is None or self.grid.obj.shape != obs.shape[:2]:
            self.grid = Grid(obs)
        g = self.grid
        if episode_start or state is None:
            state = {"count": None, "elapsed": None, "onion_in": False}
        a = _agent(obs)
        oven = tuple(np.argwhere(g.obj == 5)[0])
        oven_state = int(obs[oven][4])
        carrying_onion, carrying_soup = obs[a][2] == 1, obs[a][3] == 1
        if state["onion_in"]:
            state["count"] = 1
            state["onion_in"] = False
        elif state["count"] is not None and not carrying_soup:
            state["count"] += 1
        oven_adj = g.adjacent(5)
        bisection = self.short is not None
        counter_code = 4
        if bisection and state["elapsed"] is not None:
            counter_code = 4 if state["elapsed"] ** 2 < self.short * self.long else 8
        counter_adj = g.adjacent(counter_code)
        if carrying_soup:
            action = g.go_interact(a, g.nearest(a, counter_adj))
        elif carrying_onion:
            target = g.nearest(a, oven_adj)
            action = g.go_interact(a, target)
            if action == INTERACT:
                state["onion_in"] = True
        elif state["count"] is None:
            onion_adj = g.adjacent(3)
            best = min(onion_adj, key=lambda x: g.d(a, x) + min(g.d(x, y) for y in oven_adj))
            action = g.go_interact(a, best)
        else:
            post = min(oven_adj, key=lambda y: (min(g.d(y, c) for c in counter_adj), g.d(a, y)))
            if bisection:
                ready = oven_state == 2
                action = INTERACT if (ready and a == post) else g.towards(a, post)
                if action == INTERACT:
                    state["elapsed"] = state["count"]
            elif a == post and state["count"] >= self.td:
                action = INTERACT
            elif a == post:
                action = WAIT
            else:
                action = g.towards(a, post)
        if self.activity:
            c = -1.0 if state["count"] is None else float(state["count"])
            ramp = np.array([c, c / max(self.td or 1, 1), float(carrying_soup)], dtype=np.float32)
            return action, state, ramp
        return action, state
