#!/usr/bin/env python3
"""Golden reference traces for the two extension tasks, MultiAnchor-v0 and MultiOven-v0.

What it does
    Runs the public reference environments of decide-ugent/chronocooked
    (commit b3f83e7272c05cd17ebda149f9a3bce9a52405ff,
    singleagent/rl_environments/bisection_multi_anchors.py -> ChronoCookedBisectionMultiAnchors and
    singleagent/rl_environments/bisection_multi_oven.py    -> ChronoCookedBisectionMultiOven)
    under scripted closed-loop policies (a BFS walker over the 4x3 grid plus task logic) and
    random actions, and writes one JSON object per episode:

      {"case", "task", "set", "tds", "on_times", "start", "actions", "obs", "reward", "terminated"}

    * set      : "key=value" strings with the reference's constructor names (always
                 reference_compat=true and max_timesteps=N; MA: anchors=a,b,..; MO: n_ovens,
                 asynchronous, short_duration, long_duration). Every value is written explicitly,
                 even where it equals the class default.
    * tds      : durations actually used (MA: [oven_duration]; MO: one per oven), read from the env.
    * on_times : MO asynchronous only: oven_on_times[1..n-1] as stored after reset (and after an
                 optional overwrite, see below); null otherwise.
    * start    : the start cell the env chose, read from env.agent_position after reset.
    * obs      : hex of the uint8 (4,3,6) observation, row-major; reset observation first; one copy
                 per step (the env returns its live array).
    Episodes are run until the env reports terminated (time-out or delivery), so every case ends
    with terminated == true.

    Start cells are controlled the way the reference allows: reset(seed=s) with the smallest s >= 1
    such that random.Random(s).choice(free_positions) is the wanted cell (a few cases use seed=None,
    i.e. the global RNG). Durations are passed at reset (oven_duration= / oven_durations=), except
    in the "drawn" cases where the reference draws them from the global RNG. Asynchronous on-times
    are drawn by the reference from the global RNG (seeded per case); the "ot*" cases then overwrite
    oven_on_times[1..] and rebuild on_time_to_oven exactly as reset builds it, with distinct values
    inside the range reset samples from (range(0, 6 + d0//2 + 1)), i.e. values the reference could
    itself have drawn. Where the reference draws the on-times, a drawn on-time 0 (that oven never
    fires, so a max_timesteps=200 episode would run to the limit) is avoided by re-seeding with a
    salted case seed ("<case>#k"); the "drawnot0" cases instead re-seed until the reference itself
    draws a 0, and use a small max_timesteps.

    Case families (name = <task/config>_<family>_...): opt (correct counter, every start cell),
    wrong/wrong0/wrongall (wrong counters), probe/probeall (durations equal to no anchor / neither
    short nor long), early (interacts at the oven before ready), dispenser2 (second interact at the
    dispenser, empty-handed interacts at a counter and an off oven), soupoven (soup held at the
    oven and the dispenser, onion held at a counter, late pickup), onion2 (second onion: deadlock
    to the time limit), td0 / timeout_zero (duration 0: never ready), holdsoup / default_timeout
    (time-outs), random (uniform random actions), drawn_global (reference draws start cell and
    durations from the global RNG), edge (*_full, *_max<n-1> delivery at step max+1,
    *_max<n-2> time-out one step before it), onionoven<k> (onion held at oven k), soupfirst
    (env-started soups delivered before the onion is put), ot0/ot1/ottop (set on-times),
    default_* (class defaults written explicitly).

    Python's `random` and numpy are seeded globally at start and again per case (from a CRC of the
    case name), so the output is byte-for-byte reproducible.

How to run (from the repository root, with a Python that has gymnasium and numpy, e.g. a venv;
about 2 s on one core)
    python3 scripts/golden/extension_traces.py --reference PATH_TO_rl_environments \
        --out env/tests/golden/extension_traces.jsonl

PATH_TO_rl_environments is a folder holding the two reference files named above (e.g. extracted
with `git show b3f83e7...:singleagent/rl_environments/<file>`). No reference code lives in this
repository.
"""
import argparse
import contextlib
import io
import json
import random
import sys
import zlib
from collections import deque

import numpy as np

STAY, DOWN, UP, RIGHT, LEFT, INTERACT = 0, 1, 2, 3, 4, 5
MOVES = [(DOWN, (1, 0)), (UP, (-1, 0)), (RIGHT, (0, 1)), (LEFT, (0, -1))]

MA_SETS = [(3, 10, 20, 25), (4, 12, 18, 25), (4, 8, 12, 18), (5, 10, 15, 20)]
MO_SL = [(4, 8), (4, 12), (4, 18), (6, 12)]


def neighbours(cell):
    return [(cell[0] + d[0], cell[1] + d[1]) for _, d in MOVES]


def seed_for_cell(free, cell):
    """Smallest seed >= 1 whose random.Random(seed).choice(free) is `cell` (what reset does)."""
    for s in range(1, 100000):
        if random.Random(s).choice(free) == cell:
            return s
    raise RuntimeError("no seed")


class Episode:
    """Drives one reference env and records the trace."""

    def __init__(self, env, max_steps):
        self.env = env
        self.actions, self.obs, self.reward, self.term = [], [], [], []
        self.done = False
        self.cap = max_steps + 1

    def record_reset(self, obs):
        self.obs.append(np.array(obs, dtype=np.uint8).copy().tobytes().hex())

    def step(self, a):
        if self.done:
            return
        obs, r, term, trunc, _ = self.env.step(a)
        assert trunc is False
        self.actions.append(int(a))
        self.obs.append(np.array(obs, dtype=np.uint8).copy().tobytes().hex())
        self.reward.append(float(r))
        self.term.append(bool(term))
        if term:
            self.done = True
        assert len(self.actions) <= self.cap, "episode ran past max_timesteps+1"

    # --- walker -------------------------------------------------------------------------
    @property
    def pos(self):
        return tuple(self.env.agent_position)

    def path_to(self, goals):
        free = set(self.env.free_positions)
        start = self.pos
        if start in goals:
            return []
        prev = {start: None}
        q = deque([start])
        while q:
            cur = q.popleft()
            for a, d in MOVES:
                nxt = (cur[0] + d[0], cur[1] + d[1])
                if nxt in free and nxt not in prev:
                    prev[nxt] = (cur, a)
                    if nxt in goals:
                        acts = []
                        node = nxt
                        while prev[node] is not None:
                            node, act = prev[node]
                            acts.append(act)
                        return acts[::-1]
                    q.append(nxt)
        raise RuntimeError(f"unreachable {goals} from {start}")

    def goto_cell(self, cell):
        for a in self.path_to({cell}):
            self.step(a)

    def goto_obj(self, obj):
        goals = {c for c in neighbours(obj) if c in set(self.env.free_positions)}
        for a in self.path_to(goals):
            self.step(a)

    def interact(self, k=1):
        for _ in range(k):
            self.step(INTERACT)

    def stay(self, k=1):
        for _ in range(k):
            self.step(STAY)

    def finish(self, action=STAY):
        while not self.done:
            self.step(action)

    def wait_until(self, cond, action=STAY):
        while not self.done and not cond():
            self.step(action)

    def cell(self):
        r, c = self.pos
        return self.env.grid_map[r, c]


# ============================== Multi-anchor ==============================================

def ma_policy(ep, p):
    env = ep.env
    anchors = env.anchors
    oven = env.oven1_pos
    if p.get("counter_first") is not None:  # empty-handed interact at a counter: no-op
        ep.goto_obj(env.delivery_positions[p["counter_first"]])
        ep.interact()
    if p.get("interact_oven_empty"):  # empty-handed at an off oven: no-op
        ep.goto_obj(oven)
        ep.interact()
    ep.goto_obj(env.onion_pos)
    ep.interact()
    if p.get("double_dispenser"):
        ep.interact()
    if p.get("onion_counter") is not None:  # onion held at a counter: no-op
        ep.goto_obj(env.delivery_positions[p["onion_counter"]])
        ep.interact()
    ep.goto_obj(oven)
    ep.interact()  # put
    if p.get("second_onion"):
        ep.goto_obj(env.onion_pos)
        ep.interact()
        ep.goto_obj(oven)
        ep.finish(INTERACT)  # deadlock: nothing can be put or taken
        return
    if p.get("walk_away"):  # interact early, wander, come back and poll
        ep.interact(2)
        ep.goto_obj(env.onion_pos)
        ep.stay(2)
        ep.goto_obj(oven)
    if p.get("poll"):
        ep.wait_until(lambda: env.grid_map[ep.pos[0], ep.pos[1], 3] == 1, INTERACT)
    else:
        ep.wait_until(lambda: env.oven1_state == 2)
        ep.stay(p.get("late", 0))
        ep.interact()  # take soup
    if p.get("hold_soup"):  # keep the soup until the time limit
        ep.finish()
        return
    if p.get("soup_at_oven"):
        ep.interact(p["soup_at_oven"])
    if p.get("soup_dispenser"):  # soup held at the dispenser: no-op
        ep.goto_obj(env.onion_pos)
        ep.interact()
    ci = p["counter"]
    ep.goto_obj(env.delivery_positions[ci])
    ep.interact()


def run_ma(ref, name, anchors, td, start, policy, max_t=200, seed_mode="cell", seed_name=None):
    Env = ref["ma"]
    free = ma_free(ref, anchors)
    cs = zlib.crc32((seed_name or name).encode())
    random.seed(cs)
    np.random.seed(cs)
    env = Env(anchors=tuple(anchors), max_timesteps=max_t)
    seed = None if seed_mode == "global" else seed_for_cell(free, start)
    with contextlib.redirect_stdout(io.StringIO()):  # the reference prints drawn TDs
        obs, _ = env.reset(seed=seed, oven_duration=td)
    ep = Episode(env, max_t)
    ep._start = tuple(env.agent_position)
    ep.record_reset(obs)
    tdv = int(env.oven_duration)
    p = dict(policy)
    if p.get("counter") == "correct":
        p["counter"] = list(anchors).index(tdv)
    if p.get("kind") == "random":
        rng = np.random.RandomState(cs)
        while not ep.done:
            ep.step(int(rng.randint(0, 6)))
    else:
        ma_policy(ep, p)
        ep.finish()
    sets = ["reference_compat=true", "anchors=" + ",".join(str(a) for a in anchors),
            f"max_timesteps={max_t}"]
    return dict(case=name, task="MultiAnchor-v0", set=sets, tds=[tdv], on_times=None,
                start=list(map(int, ep._start)), actions=ep.actions, obs=ep.obs,
                reward=ep.reward, terminated=ep.term)


# ============================== Multi-oven ================================================

def mo_policy(ep, p):
    env = ep.env
    n = env.n_ovens
    S, L = env.short_duration, env.long_duration
    picked = set()
    counters = {1: env.delivery1_pos, 2: env.delivery2_pos}
    order = p.get("order", "low")
    wrong = set(p.get("wrong", []))

    def counter_for(k):
        if k in p.get("force", {}):
            return p["force"][k]
        d = env.oven_durations[k]
        if d == S:
            c = 1
        elif d == L:
            c = 2
        else:
            c = 1 if d <= (S + L) / 2 else 2
        if k in wrong:
            c = 3 - c
        return c

    def fires_later(k):
        return env.asynchronous and k >= 1 and env.oven_on_times[k] > env.timestep

    def candidates(include0=True):
        out = []
        for k in range(n):
            if k in picked or (k == 0 and not include0):
                continue
            if env.oven_timers[k] != -1 or env.oven_states[k] == 2 or fires_later(k):
                out.append(k)
        return out

    def pick_target(cands):
        ready = [k for k in cands if env.oven_states[k] == 2]
        if isinstance(order, list):
            for k in order:
                if k in cands:
                    return k
            return None
        pool = ready if ready else cands
        if not pool:
            return None
        return max(pool) if order == "high" else min(pool)

    onion_detour = p.get("onion_at_oven")
    soup_first = p.get("soup_first", False)
    guard = 0
    while not ep.done:
        guard += 1
        assert guard < 10000
        cell = ep.cell()
        if cell[3] >= 1:  # carrying soup
            k = (int(cell[3]) - 6) // 3
            picked.add(k)
            if p.get("soup_at_oven") and k == p.get("soup_at_oven_k", k):
                ep.interact(p["soup_at_oven"])
                p["soup_at_oven"] = 0
            ep.goto_obj(counters[counter_for(k)])
            ep.interact()
            continue
        if cell[2] == 1:  # carrying onion
            if onion_detour is not None:
                ep.goto_obj(env.oven_positions[onion_detour])
                ep.interact()
                onion_detour = None
                continue
            if env.oven0_deactivated:  # second onion: deadlock until the time limit
                ep.goto_obj(env.oven_positions[0])
                ep.finish(INTERACT)
                return
            ep.goto_obj(env.oven_positions[0])
            ep.interact()
            if p.get("second_onion"):
                ep.goto_obj(env.onion_pos)
                ep.interact()
            continue
        # empty hands
        pending_env = [k for k in range(1, n) if k not in picked and fires_later(k)
                       or (k >= 1 and k not in picked and env.oven_timers[k] != -1)]
        if not env.oven0_deactivated and not (soup_first and pending_env):
            ep.goto_obj(env.onion_pos)
            ep.interact()
            if p.get("double_dispenser"):
                ep.interact()
            continue
        cands = candidates(include0=env.oven0_deactivated)
        k = pick_target(cands)
        if k is None:
            ep.finish()
            return
        ep.goto_obj(env.oven_positions[k])
        if env.oven_states[k] == 2:
            ep.interact()
        else:
            ep.step(INTERACT if p.get("poll") else STAY)


def run_mo(ref, name, n, asyn, S, L, durs, start, policy, max_t=200, on_times=None,
           seed_mode="cell", seed_name=None, drawn_zero="avoid"):
    """drawn_zero: for asynchronous cases whose on-times the reference draws, "avoid" re-seeds
    (salting the case seed) until no drawn on-time is 0, "want" until one is (the never-firing
    oven; give such cases a small max_t)."""
    Env = ref["mo"]

    def make():
        return Env(short_duration=S, long_duration=L, max_timesteps=max_t, n_ovens=n,
                   asynchronous=asyn)

    free = mo_free(ref, n)
    for salt in range(1000):
        cs = zlib.crc32(((seed_name or name) + ("" if salt == 0 else f"#{salt}")).encode())
        random.seed(cs)
        np.random.seed(cs)
        env = make()
        seed = None if seed_mode == "global" else seed_for_cell(free, start)
        with contextlib.redirect_stdout(io.StringIO()):  # the reference prints drawn durations
            obs, _ = env.reset(seed=seed, oven_durations=list(durs) if durs is not None else [])
        if not asyn or n == 1 or on_times is not None:
            break
        has_zero = 0 in [env.oven_on_times[i] for i in range(1, n)]
        if has_zero == (drawn_zero == "want"):
            break
    if on_times is not None:
        assert asyn
        upper = 6 + env.oven_durations[0] // 2
        assert len(on_times) == n - 1 and len(set(on_times)) == n - 1
        assert all(0 <= t <= upper for t in on_times), (on_times, upper)
        for i, t in enumerate(on_times, start=1):
            env.oven_on_times[i] = t
        env.on_time_to_oven = {v: k for k, v in env.oven_on_times.items()}
    ep = Episode(env, max_t)
    ep._start = tuple(env.agent_position)
    ep.record_reset(obs)
    tds = [int(env.oven_durations[i]) for i in range(n)]
    ots = [int(env.oven_on_times[i]) for i in range(1, n)] if asyn else None
    if policy.get("kind") == "random":
        rng = np.random.RandomState(cs)
        while not ep.done:
            ep.step(int(rng.randint(0, 6)))
    else:
        mo_policy(ep, dict(policy))
        ep.finish()
    sets = ["reference_compat=true", f"n_ovens={n}", f"asynchronous={'true' if asyn else 'false'}",
            f"short_duration={S}", f"long_duration={L}", f"max_timesteps={max_t}"]
    return dict(case=name, task="MultiOven-v0", set=sets, tds=tds, on_times=ots,
                start=list(map(int, ep._start)), actions=ep.actions, obs=ep.obs,
                reward=ep.reward, terminated=ep.term)


# ============================== case lists ================================================

def ma_free(ref, anchors):
    e = ref["ma"](anchors=tuple(anchors))
    with contextlib.redirect_stdout(io.StringIO()):
        e.reset(seed=1, oven_duration=1)
    return list(e.free_positions)


def mo_free(ref, n):
    e = ref["mo"](n_ovens=n)
    with contextlib.redirect_stdout(io.StringIO()):
        e.reset(seed=1, oven_durations=[1] * n)
    return list(e.free_positions)


def tag(anchors):
    return "-".join(str(a) for a in anchors)


def rc(cell):
    return f"{cell[0]}{cell[1]}"


def ma_cases(ref):
    """(name, kwargs for run_ma) for every multi-anchor case."""
    configs = []
    for full in MA_SETS:
        for k in (2, 3, 4):
            a = full[:k]
            if a not in configs:
                configs.append(a)
    out = []
    for ci, a in enumerate(configs):
        free = ma_free(ref, a)
        k = len(a)
        t = tag(a)
        # 1. optimal delivery from every start cell, cycling the anchors
        for j, cell in enumerate(free):
            td = a[(j + ci) % k]
            out.append((f"ma_{t}_opt_td{td}_s{rc(cell)}",
                        dict(anchors=a, td=td, start=cell, policy={"counter": "correct"})))
        # 2. every anchor delivered to a wrong counter (cycling); the first one polls the oven
        for i, td in enumerate(a):
            wc = (i + 1 + ci) % k
            cell = free[(i * 3 + ci) % len(free)]
            pol = {"counter": wc}
            if i == 0:
                pol["poll"] = True
            out.append((f"ma_{t}_wrong_td{td}_c{wc + 1}_s{rc(cell)}",
                        dict(anchors=a, td=td, start=cell, policy=pol)))
        # 3. probes equal to no anchor: pay 0 at any counter
        allp = sorted({1, a[0] + 1, (a[0] + a[1]) // 2, a[-1] - 1, a[-1] + 4} - set(a))
        probes = [allp[(ci + i) % len(allp)] for i in range(3)]
        for i, td in enumerate(sorted(set(probes))):
            c = (i + ci) % k
            cell = free[(i * 2 + 1 + ci) % len(free)]
            out.append((f"ma_{t}_probe_td{td}_c{c + 1}_s{rc(cell)}",
                        dict(anchors=a, td=td, start=cell, policy={"counter": c})))
        # 4. edge cases
        td = a[ci % k]
        c0 = free[ci % len(free)]
        c1 = free[(ci + 3) % len(free)]
        out.append((f"ma_{t}_early_td{td}_s{rc(c0)}",
                    dict(anchors=a, td=td, start=c0,
                         policy={"counter": "correct", "walk_away": True, "poll": True})))
        out.append((f"ma_{t}_dispenser2_td{td}_s{rc(c1)}",
                    dict(anchors=a, td=td, start=c1,
                         policy={"counter": "correct", "double_dispenser": True,
                                 "counter_first": (ci + 1) % k, "interact_oven_empty": True})))
        out.append((f"ma_{t}_soupoven_td{a[-1]}_s{rc(c0)}",
                    dict(anchors=a, td=a[-1], start=c0,
                         policy={"counter": "correct", "soup_at_oven": 2, "soup_dispenser": True,
                                 "onion_counter": ci % k, "late": 3})))
        out.append((f"ma_{t}_onion2_td{a[0]}_s{rc(c1)}",
                    dict(anchors=a, td=a[0], start=c1, max_t=a[0] + 16,
                         policy={"second_onion": True})))
        out.append((f"ma_{t}_td0_s{rc(c0)}",
                    dict(anchors=a, td=0, start=c0, max_t=20 + ci % 3 * 5,
                         policy={"counter": 0, "poll": True})))
        out.append((f"ma_{t}_holdsoup_td{a[0]}_s{rc(c1)}",
                    dict(anchors=a, td=a[0], start=c1, max_t=30 + ci % 2 * 8,
                         policy={"counter": 0, "hold_soup": True})))
        cell = free[(ci + 2) % len(free)]
        out.append((f"ma_{t}_random_s{rc(cell)}",
                    dict(anchors=a, td=a[ci % k], start=cell, max_t=[30, 60][ci % 2],
                         policy={"kind": "random"})))
        # drawn TD (the reference's random.choice over the anchors), global-RNG start cell
        out.append((f"ma_{t}_drawn_global",
                    dict(anchors=a, td=None, start=None, seed_mode="global",
                         policy={"counter": "correct"})))
        # time-limit edges (every other config): the optimal episode has n steps;
        # max = n-1 -> delivery at step max+1, max = n-2 -> time-out one step before it
        if ci % 2 == 0:
            out.append((f"ma_{t}_edge_td{td}_s{rc(c1)}",
                        dict(anchors=a, td=td, start=c1, policy={"counter": "correct"},
                             edge=True)))
    # class default anchors (4,8,12) and the class default max_timesteps (100)
    a = (4, 8, 12)
    free = ma_free(ref, a)
    for j, cell in enumerate(free):
        td = a[j % 3]
        out.append((f"ma_default_opt_td{td}_s{rc(cell)}",
                    dict(anchors=a, td=td, start=cell, max_t=100, policy={"counter": "correct"})))
    out.append(("ma_default_timeout_max100", dict(anchors=a, td=12, start=free[0], max_t=100,
                                                   policy={"counter": 0, "hold_soup": True})))
    return out


def mo_cases(ref):
    """(name, kwargs for run_mo) for every multi-oven case."""
    out = []
    ci = 0
    for n in (1, 2, 3):
        free = mo_free(ref, n)
        ni = 0  # config index within this n
        for asyn in (False, True):
            for S, L in MO_SL:
                ci += 1
                mode = "async" if asyn else "sync"
                t = f"mo_n{n}_{mode}_{S}-{L}"
                base = dict(n=n, asyn=asyn, S=S, L=L)
                # 1. two (n=1) or three start cells per config (every cell covered at least twice
                #    within each n), durations cycling through short/long patterns, correct
                #    counters, low/high emptying order
                per = 2 if n == 1 else 3
                for jj in range(per):
                    j = ni * per + jj
                    cell = free[j % len(free)]
                    bits = (j * 5 + ci) % (2 ** n)
                    durs = [L if (bits >> i) & 1 else S for i in range(n)]
                    order = ["low", "high"][j % 2]
                    out.append((f"{t}_opt_{'-'.join(map(str, durs))}_{order}_s{rc(cell)}",
                                dict(base, durs=durs, start=cell, policy={"order": order})))
                ni += 1
                c0 = free[ci % len(free)]
                c1 = free[(ci + 2) % len(free)]
                c2 = free[(ci + 4) % len(free)]
                # 2. wrong counters (partial 1/n for n>1)
                durs = [S if i % 2 == 0 else L for i in range(n)]
                out.append((f"{t}_wrong0_{'-'.join(map(str, durs))}_s{rc(c0)}",
                            dict(base, durs=durs, start=c0, policy={"wrong": [0]})))
                if n > 1:
                    out.append((f"{t}_wrongall_{'-'.join(map(str, durs))}_s{rc(c1)}",
                                dict(base, durs=durs, start=c1,
                                     policy={"wrong": list(range(n)), "order": "high"})))
                # 3. probes (neither short nor long) mixed with S/L
                pr = [S + 1, L - 1, (S + L) // 2, 1, L + 4, S - 1]
                durs = [pr[(ci + i) % len(pr)] for i in range(n)]
                if n > 1:
                    durs[1] = [S, L][ci % 2]
                out.append((f"{t}_probe_{'-'.join(map(str, durs))}_s{rc(c2)}",
                            dict(base, durs=durs, start=c2, policy={"poll": True})))
                # 4. the same probe for every oven (as the evaluation does), forced counters
                d = pr[ci % len(pr)]
                out.append((f"{t}_probeall_{d}_s{rc(c1)}",
                            dict(base, durs=[d] * n, start=c1,
                                 policy={"force": {k: 1 + (k + ci) % 2 for k in range(n)}})))
                # 5. second onion deadlock / onion held at oven 1 or 2 / soup held at its oven
                if ci % 2 == 0:
                    out.append((f"{t}_onion2_{L}_s{rc(c0)}",
                                dict(base, durs=[L] * n, start=c0, max_t=24 + L % 10,
                                     policy={"second_onion": True})))
                else:
                    out.append((f"{t}_soupoven_s{rc(c1)}",
                                dict(base, durs=[L, S, L][:n], start=c1,
                                     policy={"soup_at_oven": 2,
                                             "order": [n - 1 - i for i in range(n)]})))
                if n > 1:
                    k = 1 + ci % (n - 1)
                    out.append((f"{t}_onionoven{k}_s{rc(c2)}",
                                dict(base, durs=[S, L, S][:n], start=c2,
                                     policy={"onion_at_oven": k, "double_dispenser": True})))
                # 6. random actions / an oven of duration 0 (never ready: time-out)
                if ci % 2 == 1:
                    out.append((f"{t}_random_s{rc(c2)}",
                                dict(base, durs=[S, L, S][:n], start=c2, max_t=40,
                                     policy={"kind": "random"})))
                else:
                    out.append((f"{t}_timeout_zero_s{rc(c0)}",
                                dict(base, durs=[0] + [S] * (n - 1), start=c0, max_t=22,
                                     policy={"poll": True})))
                # 7. durations drawn by the reference (global RNG), global-RNG start cell
                if ci % 2 == 0:
                    out.append((f"{t}_drawn_global",
                                dict(base, durs=None, start=None, seed_mode="global",
                                     policy={})))
                # 8. time-limit edges (every other config)
                if ci % 2 == 1:
                    out.append((f"{t}_edge_s{rc(c2)}",
                                dict(base, durs=[S, L, L][:n], start=c2, policy={}, edge=True)))
                # 9. asynchronous specials: soups of env-started ovens delivered before the
                #    onion is put; on-times 0 (never fires), 1, and the top of the range;
                #    an on-time 0 drawn by the reference itself
                if asyn and n > 1:
                    top = 6 + S // 2
                    top_l = 6 + L // 2
                    out.append((f"{t}_soupfirst_s{rc(c0)}",
                                dict(base, durs=[S] + [L, S][:n - 1], start=c0,
                                     on_times=[1, 3][:n - 1], policy={"soup_first": True})))
                    out.append((f"{t}_ot0_s{rc(c1)}",
                                dict(base, durs=[S] * n, start=c1, max_t=30,
                                     on_times=[0, top][:n - 1], policy={})))
                    out.append((f"{t}_ot1_s{rc(c2)}",
                                dict(base, durs=[L] * n, start=c2,
                                     on_times=[1, 2][:n - 1], policy={"order": "high"})))
                    out.append((f"{t}_ottop_s{rc(c0)}",
                                dict(base, durs=[L] + [S, L][:n - 1], start=c0,
                                     on_times=[top_l, top_l - 1][:n - 1],
                                     policy={"order": "high"})))
                    out.append((f"{t}_ottop_poll_s{rc(c1)}",
                                dict(base, durs=[S] + [1, L][:n - 1], start=c1,
                                     on_times=[top, 1][:n - 1], policy={"poll": True})))
                    if ci % 2 == 0:
                        out.append((f"{t}_drawnot0_s{rc(c2)}",
                                    dict(base, durs=[S, L, S][:n], start=c2, max_t=36,
                                         drawn_zero="want", policy={"soup_first": True})))
    # class defaults: short 6 / long 12, n_ovens 2, synchronous, max_timesteps 100
    free = mo_free(ref, 2)
    for j, cell in enumerate(free):
        durs = [[6, 12], [12, 6], [6, 6], [12, 12]][j % 4]
        out.append((f"mo_default_opt_{durs[0]}-{durs[1]}_s{rc(cell)}",
                    dict(n=2, asyn=False, S=6, L=12, durs=durs, start=cell, max_t=100,
                         policy={})))
    return out


def run_case(ref, name, kw):
    kw = dict(kw)
    edge = kw.pop("edge", False)
    task = "ma" if "anchors" in kw else "mo"

    def once(nm, **over):
        k2 = dict(kw, seed_name=name, **over)
        if task == "ma":
            return run_ma(ref, nm, **k2)
        return run_mo(ref, nm, **k2)

    if not edge:
        return [once(name)]
    first = once(name + "_full")
    n = len(first["actions"])
    assert first["terminated"][-1] and sum(first["reward"]) > 0
    assert n <= int(first["set"][-1].split("=")[1]), "edge base case must end by delivery"
    return [first, once(name + "_max%d" % (n - 1), max_t=n - 1),
            once(name + "_max%d" % (n - 2), max_t=n - 2)]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--reference", required=True,
                    help="folder holding bisection_multi_anchors.py and bisection_multi_oven.py")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    random.seed(0)
    np.random.seed(0)
    sys.path.insert(0, a.reference)
    import bisection_multi_anchors as ma_mod  # noqa: E402  (reference code, from --reference)
    import bisection_multi_oven as mo_mod  # noqa: E402
    ref = {"ma": ma_mod.ChronoCookedBisectionMultiAnchors,
           "mo": mo_mod.ChronoCookedBisectionMultiOven}
    rows = []
    for name, kw in ma_cases(ref) + mo_cases(ref):
        rows.extend(run_case(ref, name, kw))
    names = [r["case"] for r in rows]
    assert len(names) == len(set(names)), "duplicate case names"
    for r in rows:
        assert len(r["obs"]) == len(r["actions"]) + 1 == len(r["reward"]) + 1 == len(r["terminated"]) + 1
        assert r["terminated"][-1] and not any(r["terminated"][:-1])
    with open(a.out, "w") as f:
        for r in rows:
            f.write(json.dumps(r, separators=(",", ":")) + "\n")
    print(f"wrote {len(rows)} cases to {a.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
