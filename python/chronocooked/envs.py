"""gymnasium environments backed by the Rust envs.

``ChronoEnv``: one env (``gymnasium.Env``); ``ChronoVectorEnv``: N envs stepped in Rust
(``gymnasium.vector.VectorEnv``). Keyword arguments are the task parameters with the names
of ``chronocooked --set`` (reference aliases such as ``oven_duration``, ``max_timesteps``,
``undercooked_possible``, ``reference_compat`` included), plus ``obs_mode`` and
``render_mode``.
"""

from __future__ import annotations

import json
import numpy as np
import gymnasium
from gymnasium import spaces
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from . import _core

def _value(key, v):
    if isinstance(v, (bool, np.bool_)):
        return "true" if v else "false"
    if isinstance(v, (list, tuple, np.ndarray)):
        return ",".join(_value(key, x) for x in v)
    if isinstance(v, (int, np.integer, float, np.floating, str)):
        return str(v)
    raise ValueError(
        f"invalid value for `{key}`: {v!r} (allowed: a number, string, bool or list of numbers)"
    )


def overrides(params: dict) -> list[str]:
    """Task parameters as the ``key=value`` overrides of the Rust registry."""
    return [f"{k}={_value(k, v)}" for k, v in params.items()]


def task_ids() -> list[str]:
    """Ids of every registered task (``FixedInterval-v0``, …)."""
    return [t["id"] for t in _core.tasks()]


def reset_options(task: str) -> list[dict]:
    """The options ``reset(options=…)`` takes on ``task``, as its family declares them: a list
    of dicts with ``key`` and ``doc`` (value and meaning)."""
    # The registry's id of `task` (an alias such as ``fixedinterval`` included); an unknown
    # task raises the registry's error, naming the registered ones.
    canonical = json.loads(_core.resolve(task, []))["id"]
    return next(t["reset_options"] for t in _core.tasks() if t["id"] == canonical)


def _obs_space(core) -> spaces.Box:
    shape = tuple(core.obs_shape)
    if core.obs_mode == "codes":
        return spaces.Box(0, int(core.obs_high), shape, np.uint8)
    return spaces.Box(0.0, float(core.obs_high), shape, np.float32)


class ChronoEnv(gymnasium.Env):
    """One Chronocooked task (the Rust env).

    Observations: ``obs_mode="codes"`` the reference encoding, ``uint8 [R, C, 6]``;
    ``"onehot"`` the network view, ``float32 [channels, R, C]``. Actions: ``Discrete(6)``
    (0 wait, 1 down, 2 up, 3 right, 4 left, 5 interact). ``reset(seed, options)`` options are
    those the task's family declares (``reset_options(task)``): ``start`` (row, col) and ``td``
    (steps) on every task, ``never_ready`` (uncertainty), ``oven_tds`` and ``on_times``
    (multi-oven), ``prior`` and ``gain`` (reproduction). ``info`` holds
    the Rust ``Info`` fields as plain values (timers in steps, −1 = off).
    """

    metadata = {"render_modes": ["ansi", "rgb_array"], "render_fps": 4}

    def __init__(self, task: str = "FixedInterval-v0", obs_mode: str = "codes",
                 render_mode: str | None = None, **params):
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise ValueError(
                f"invalid value for `render_mode`: {render_mode!r} (allowed: None, 'ansi', 'rgb_array')"
            )
        self.task = task
        self.params = dict(params)
        self._core = _core.Env(task, overrides(params), obs_mode)
        self.render_mode = render_mode
        self.observation_space = _obs_space(self._core)
        self.action_space = spaces.Discrete(self._core.n_actions)
        self._seeded = False
        self._needs_reset = True

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        super().reset(seed=seed)
        if seed is None and not self._seeded:
            # First reset without a seed: draw one from gymnasium's RNG (itself seeded from
            # entropy), as gymnasium envs do.
            seed = int(self.np_random.integers(0, 2**63 - 1))
        if seed is not None:
            seed = int(seed)
            if seed < 0:
                raise ValueError(f"invalid value for `seed`: {seed} (allowed: an integer >= 0)")
        self._seeded = True
        out = self._core.reset(seed, options)
        self._needs_reset = False
        return out

    def step(self, action):
        if self._needs_reset:
            raise gymnasium.error.ResetNeeded("call reset() before step()")
        if isinstance(action, np.ndarray):
            if action.size != 1:
                raise ValueError(
                    f"invalid action {action!r} (allowed: one integer in 0..=5)")
            action = action.reshape(()).item()
        if isinstance(action, (bool, np.bool_)) or not isinstance(action, (int, np.integer)):
            raise ValueError(
                f"invalid action {action!r} (allowed: an integer 0 wait, 1 down, 2 up, 3 right, 4 left, 5 interact)"
            )
        return self._core.step(int(action))

    def render(self):
        if self.render_mode == "ansi":
            return self._core.render_ansi()
        if self.render_mode == "rgb_array":
            return self._core.render_rgb()
        return None

    def free_cells(self) -> list[tuple[int, int]]:
        """The free cells ``(row, col)`` (possible start cells), row-major."""
        return self._core.free_cells()


class ChronoVectorEnv(VectorEnv):
    """N Chronocooked envs stepped together in Rust.

    Autoreset: gymnasium's next-step mode by default (an env that ended is reset on the
    following ``step``, its action ignored, reward 0); ``autoreset_mode="same_step"`` resets
    within the step and puts the last observation / info in ``info["final_obs"]`` /
    ``info["final_info"]`` (mask ``info["_final_obs"]``). ``reset(seed=s)`` seeds env ``i``
    with ``s + i`` (a list gives one seed per env), like gymnasium's ``SyncVectorEnv``.

    ``info`` is a dict of arrays ``[N]``: the fields of the Rust ``Info`` with ``counter``
    (−1 none, 0 main, 1 short, 2 long), ``carrying`` (0 nothing, 1 onion, 2 soup) and
    ``events`` (bit set, ``chronocooked.EVENT_FLAGS``) as integer codes and ``agent`` ``[N, 2]``.
    """

    metadata = {"autoreset_mode": AutoresetMode.NEXT_STEP, "render_modes": []}

    def __init__(self, num_envs: int = 1, task: str = "FixedInterval-v0", obs_mode: str = "codes",
                 autoreset_mode: AutoresetMode | str = AutoresetMode.NEXT_STEP, render_mode=None,
                 **params):
        if render_mode is not None:
            raise ValueError(
                f"invalid value for `render_mode`: {render_mode!r} (allowed: None for the vector env; render a ChronoEnv)"
            )
        if isinstance(autoreset_mode, str) and not isinstance(autoreset_mode, AutoresetMode):
            aliases = {"next_step": AutoresetMode.NEXT_STEP, "same_step": AutoresetMode.SAME_STEP}
            autoreset_mode = aliases.get(autoreset_mode, autoreset_mode)
        try:
            mode = AutoresetMode(autoreset_mode)
        except ValueError:
            raise ValueError(
                f"invalid value for `autoreset_mode`: {autoreset_mode!r} (allowed: next_step, same_step)"
            ) from None
        if mode not in (AutoresetMode.NEXT_STEP, AutoresetMode.SAME_STEP):
            raise ValueError(
                f"invalid value for `autoreset_mode`: {autoreset_mode!r} (allowed: next_step, same_step)"
            )
        self.task = task
        self.params = dict(params)
        self.num_envs = int(num_envs)
        self._core = _core.VecEnv(task, self.num_envs, overrides(params), obs_mode,
                                  "next_step" if mode == AutoresetMode.NEXT_STEP else "same_step")
        self.metadata = {"autoreset_mode": mode, "render_modes": []}
        self.render_mode = None
        self.single_observation_space = _obs_space(self._core)
        self.single_action_space = spaces.Discrete(6)
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = spaces.MultiDiscrete(np.full(self.num_envs, 6))
        self._seeded = False

    def reset(self, *, seed=None, options: dict | None = None):
        n = self.num_envs
        if seed is None or isinstance(seed, (int, np.integer)):
            super().reset(seed=None if seed is None else int(seed))
        elif len(seed) != n:
            raise ValueError(
                f"invalid value for `seed`: {len(seed)} seeds (allowed: one int, or exactly {n})")
        mask = None
        if options is not None and options.get("reset_mask") is not None:
            mask = [bool(x) for x in np.asarray(options["reset_mask"]).reshape(-1)]
        if seed is None:
            if self._seeded:
                seeds = [None] * n
            else:
                seeds = [int(x) for x in self.np_random.integers(0, 2**63 - 1, size=n)]
        elif isinstance(seed, (int, np.integer)):
            seeds = [int(seed) + i for i in range(n)]
        else:
            seeds = [None if s is None else int(s) for s in seed]
        if any(s is not None and s < 0 for s in seeds):
            raise ValueError(f"invalid value for `seed`: {seed} (allowed: integers >= 0)")
        self._seeded = True
        return self._core.reset(seeds, mask, options)

    def step(self, actions):
        return self._core.step(actions)


def register_envs() -> None:
    """Registers every task as ``chronocooked/<Id>`` (idempotent)."""
    for task in task_ids():
        env_id = f"chronocooked/{task}"
        if env_id in gymnasium.registry:
            continue
        gymnasium.register(
            id=env_id,
            entry_point="chronocooked.envs:ChronoEnv",
            vector_entry_point="chronocooked.envs:ChronoVectorEnv",
            kwargs={"task": task},
            # gym.make returns the env itself: it enforces reset-before-step on its own and
            # passes check_env (tests), so gymnasium's checker/order wrappers add nothing but
            # a wrapped-env warning in check_env and ~15% per step.
            disable_env_checker=True,
            order_enforce=False,
        )
