"""The gymnasium envs: registration, spaces, check_env, golden traces of the original
implementation, reset options, info, fresh arrays, vector = scalar, errors."""

import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import chronocooked

TASKS = chronocooked.task_ids()
INFO_KEYS = ["timestep", "td", "oven_timer", "timer_at_action", "oven_state", "oven_off_time",
             "counter", "events", "next_to_oven", "agent", "carrying", "never_ready",
             "manual_stop_time", "sink_count", "last_sink_timer"]


def test_every_task_is_registered():
    assert len(TASKS) >= 6
    for t in TASKS:
        assert f"chronocooked/{t}" in gym.registry
    assert "chronocooked/Bisection-v0" in gym.registry


@pytest.mark.parametrize("task", TASKS)
@pytest.mark.parametrize("obs_mode", ["codes", "onehot"])
def test_check_env_passes_with_warnings_as_errors(task, obs_mode):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for render_mode in ["ansi", "rgb_array"]:
            env = gym.make(f"chronocooked/{task}", obs_mode=obs_mode, render_mode=render_mode)
            check_env(env)  # gym.make returns the env itself (no wrapper)
            check_env(env.unwrapped)
            env.close()


def test_spaces_are_exact():
    env = gym.make("chronocooked/Bisection-v0", short=4, long=12)
    space = env.observation_space
    assert space.dtype == np.uint8 and space.shape == (4, 3, 6)
    assert space.low.min() == 0 and space.high.max() == 8  # the long counter's code
    onehot = gym.make("chronocooked/Bisection-v0", obs_mode="onehot").observation_space
    assert onehot.dtype == np.float32 and onehot.shape[1:] == (4, 3)
    assert env.action_space == gym.spaces.Discrete(6)
    # Every observation of a long random run lies in the space and reaches its bounds.
    rng = np.random.default_rng(0)
    seen_max = 0
    obs, _ = env.reset(seed=0)
    for _ in range(3000):
        obs, _, term, trunc, _ = env.step(int(rng.integers(6)))
        assert space.contains(obs)
        seen_max = max(seen_max, int(obs.max()))
        if term or trunc:
            obs, _ = env.reset()
    assert seen_max == 8


def test_golden_traces_of_the_original_replay_step_for_step(golden_cases):
    steps = 0
    for c in golden_cases:
        params = dict(kv.split("=", 1) for kv in c["set"])
        env = gym.make(f"chronocooked/{c['task']}", **params)
        obs, _ = env.reset(seed=0, options={"start": tuple(c["start"]), "td": c["td"]})
        assert obs.tobytes().hex() == c["obs"][0], c["case"]
        for i, a in enumerate(c["actions"]):
            obs, r, term, trunc, _ = env.step(a)
            assert obs.tobytes().hex() == c["obs"][i + 1], (c["case"], i)
            assert abs(r - c["reward"][i]) < 1e-6, (c["case"], i)
            assert term == c["terminated"][i], (c["case"], i)
            assert not trunc, (c["case"], i)  # reference_compat: the time limit terminates
            steps += 1
    assert len(golden_cases) == 631 and steps > 5000


def test_extension_golden_traces_replay_through_gymnasium_make(extension_cases):
    """The reference's multi-anchor and multi-oven episodes, through ``gymnasium.make`` with
    the reference's parameter names and the per-oven reset options."""
    steps = 0
    tasks = set()
    for c in extension_cases:
        params = dict(kv.split("=", 1) for kv in c["set"])
        env = gym.make(f"chronocooked/{c['task']}", **params)
        options = {"start": tuple(c["start"])}
        if c["task"].startswith("MultiOven"):
            options["oven_tds"] = c["tds"]
            if c["on_times"] is not None:
                options["on_times"] = c["on_times"]
        else:
            options["td"] = c["tds"][0]
        obs, _ = env.reset(seed=0, options=options)
        assert obs.tobytes().hex() == c["obs"][0], c["case"]
        for i, a in enumerate(c["actions"]):
            obs, r, term, trunc, _ = env.step(a)
            assert obs.tobytes().hex() == c["obs"][i + 1], (c["case"], i)
            assert abs(r - c["reward"][i]) < 1e-6, (c["case"], i)
            assert term == c["terminated"][i], (c["case"], i)
            assert not trunc, (c["case"], i)
            steps += 1
        tasks.add(c["task"])
    assert tasks == {"MultiAnchor-v0", "MultiOven-v0"}
    assert len(extension_cases) >= 500 and steps > 10000


def test_multi_oven_reset_options_and_info():
    env = gym.make("chronocooked/MultiOven-v0", n_ovens=3, asynchronous=True)
    _, info = env.reset(seed=2, options={"oven_tds": [4, 12, 4], "on_times": [3, 7]})
    assert info["ovens"]["td"] == [4, 12, 4]
    assert info["ovens"]["on_time"] == [-1, 3, 7]
    with pytest.raises(ValueError, match="on_times"):
        env.reset(seed=2, options={"on_times": [3, 300]})
    with pytest.raises(ValueError, match="oven_tds"):
        env.reset(seed=2, options={"oven_tds": [4, 12]})
    a = gym.make("chronocooked/MultiAnchor-v0", anchors=[3, 10, 20, 25])
    _, info = a.reset(seed=0, options={"td": 20})
    assert info["td"] == 20
    with pytest.raises(ValueError, match="anchors"):
        gym.make("chronocooked/MultiAnchor-v0", anchors=[3, 10, 20, 25, 30])


def test_reference_aliases_and_reset_options():
    env = gym.make("chronocooked/FixedInterval-v0", oven_duration=7, max_timesteps=50,
                   reference_compat=True)
    obs, info = env.reset(seed=1, options={"start": (4, 2)})
    assert info["td"] == 7 and info["agent"] == (4, 2)
    obs, info = env.reset(seed=1, options={"start": (0, 0), "td": 3})
    assert info["td"] == 3 and info["agent"] == (0, 0)
    u = gym.make("chronocooked/Uncertainty-v0")
    _, info = u.reset(seed=0, options={"never_ready": True})
    assert info["never_ready"] is True
    _, info = u.reset(seed=0, options={"never_ready": False})
    assert info["never_ready"] is False
    with pytest.raises(ValueError, match="unknown reset option"):
        env.reset(options={"speed": 2})
    with pytest.raises(ValueError, match="start"):
        env.reset(options={"start": (0, 1)})  # the onion dispenser's cell


def test_reset_options_are_the_task_familys_declaration():
    keys = {t: [o["key"] for o in chronocooked.reset_options(t)] for t in chronocooked.task_ids()}
    assert keys["FixedInterval-v0"] == ["start", "td"]
    assert keys["Uncertainty-v0"] == ["start", "td", "never_ready"]
    assert keys["MultiOven-v0"] == ["start", "td", "oven_tds", "on_times"]
    assert keys["Reproduction-v0"] == ["start", "td", "prior", "gain"]
    assert all(o["doc"] for t in keys for o in chronocooked.reset_options(t))
    fi = gym.make("chronocooked/FixedInterval-v0")
    # An option of another family: refused, naming this task's options and the tasks that
    # take it.
    with pytest.raises(ValueError, match=r"FixedInterval-v0 \(its options: start, td\).*Uncertainty-v0"):
        fi.reset(seed=0, options={"never_ready": True})
    # An unknown key: the task's options with their values.
    with pytest.raises(ValueError, match=r"unknown reset option `speed` for FixedInterval-v0.*td: integer"):
        fi.reset(seed=0, options={"speed": 2})
    with pytest.raises(ValueError, match=r"invalid reset option `start`"):
        fi.reset(seed=0, options={"start": (1, 2, 3)})
    with pytest.raises(ValueError, match=r"invalid reset option `td`"):
        fi.reset(seed=0, options={"td": -3})
    with pytest.raises(ValueError, match=r"invalid value for `options`"):
        fi.reset(seed=0, options=[("td", 3)])
    # numpy values read as their Python ones; None means "draw it".
    _, info = fi.reset(seed=0, options={"start": np.array([0, 0]), "td": np.int64(5), "never_ready": None})
    assert info["td"] == 5 and info["agent"] == (0, 0)
    with pytest.raises(ValueError, match="unknown task|registered"):
        chronocooked.reset_options("NoSuchTask-v0")


def test_info_carries_the_rust_fields_as_plain_values():
    env = gym.make("chronocooked/FixedInterval-v0", td=3)
    _, info = env.reset(seed=0, options={"start": (0, 0)})
    assert list(info) == INFO_KEYS
    _, _, _, _, info = env.step(5)
    assert info["events"] == ["onion_taken"] and info["carrying"] == "onion"
    assert isinstance(info["agent"], tuple) and isinstance(info["timestep"], int)
    for a in [1, 1, 5, 0, 0, 0, 5]:
        _, r, term, trunc, info = env.step(a)
    assert "pickup" in info["events"] and info["oven_off_time"] == 4
    assert info["counter"] is None and info["carrying"] == "soup"


def test_returned_arrays_are_fresh():
    env = gym.make("chronocooked/FixedInterval-v0")
    obs0, _ = env.reset(seed=0)
    keep = obs0.copy()
    obs1, *_ = env.step(1)
    obs0[:] = 99  # writing into a returned array changes nothing in the env
    obs2, *_ = env.step(0)
    assert not np.shares_memory(obs1, obs2) and not np.shares_memory(obs0, obs1)
    assert obs2.max() < 99 and not np.array_equal(obs0, keep)
    v = gym.make_vec("chronocooked/FixedInterval-v0", num_envs=3,
                     vectorization_mode="vector_entry_point")
    a, _ = v.reset(seed=0)
    b, *_ = v.step(np.zeros(3, dtype=np.int64))
    assert not np.shares_memory(a, b)


def test_same_seed_same_episode():
    def run(seed):
        env = gym.make("chronocooked/MultiTimer-v0")
        obs, info = env.reset(seed=seed)
        rng = np.random.default_rng(5)
        out = [obs.tobytes(), info["td"]]
        for _ in range(400):
            obs, r, term, trunc, info = env.step(int(rng.integers(6)))
            out.append((obs.tobytes(), r, term, trunc, info["td"]))
            if term or trunc:
                obs, info = env.reset()
                out.append((obs.tobytes(), info["td"]))
        return out

    assert run(11) == run(11)
    assert run(11) != run(12)


def _vector_vs_scalar(task, n, seed, steps, autoreset, **params):
    vec = gym.make_vec(f"chronocooked/{task}", num_envs=n,
                       vectorization_mode="vector_entry_point", autoreset_mode=autoreset, **params)
    envs = [gym.make(f"chronocooked/{task}", **params) for _ in range(n)]
    vobs, vinfo = vec.reset(seed=seed)
    for i, e in enumerate(envs):
        obs, info = e.reset(seed=seed + i)
        assert np.array_equal(vobs[i], obs)
        assert vinfo["td"][i] == info["td"]
    rng = np.random.default_rng(seed)
    done = [False] * n
    episodes = 0
    for _ in range(steps):
        actions = rng.integers(0, 6, n)
        vobs, vr, vterm, vtrunc, vinfo = vec.step(actions)
        for i, e in enumerate(envs):
            if autoreset == "next_step" and done[i]:
                obs, info = e.reset()
                r, term, trunc = 0.0, False, False
                done[i] = False
            else:
                obs, r, term, trunc, info = e.step(int(actions[i]))
                if term or trunc:
                    episodes += 1
                    if autoreset == "same_step":
                        assert vinfo["_final_obs"][i]
                        assert np.array_equal(vinfo["final_obs"][i], obs)
                        assert vinfo["final_info"]["timestep"][i] == info["timestep"]
                        obs, info = e.reset()
                    else:
                        done[i] = True
            assert np.array_equal(vobs[i], obs), (i, "obs")
            assert vr[i] == r and vterm[i] == term and vtrunc[i] == trunc
            assert vinfo["timestep"][i] == info["timestep"]
            assert vinfo["oven_timer"][i] == info["oven_timer"]
            assert tuple(vinfo["agent"][i]) == info["agent"]
            names = [k for k, bit in chronocooked.EVENT_FLAGS.items() if vinfo["events"][i] & bit]
            assert names == info["events"]
    return episodes


@pytest.mark.parametrize("task", ["FixedInterval-v0", "Bisection-v0", "MultiTimer-v0",
                                  "Uncertainty-v0"])
def test_vector_env_equals_scalar_envs_with_consecutive_seeds(task):
    assert _vector_vs_scalar(task, 6, 40, 700, "next_step", max_timesteps=40) > 20


def test_vector_env_same_step_autoreset_reports_final_obs():
    assert _vector_vs_scalar("FixedInterval-v0", 5, 3, 400, "same_step", max_timesteps=30) > 10


def test_vector_reset_mask_and_seed_list():
    v = gym.make_vec("chronocooked/FixedInterval-v0", num_envs=3,
                     vectorization_mode="vector_entry_point")
    a, _ = v.reset(seed=[5, 6, 7])
    b, _ = v.reset(seed=5)
    assert np.array_equal(a, b)
    for _ in range(3):
        v.step(np.array([1, 1, 1]))
    moved, _ = v.reset(options={"reset_mask": [True, False, False], "start": (4, 0)})
    assert moved[0, 4, 0, 1] == 1  # env 0 restarted at (4, 0)


def test_bad_parameters_and_actions_raise_clear_errors():
    with pytest.raises(ValueError, match=r"`td`.*allowed"):
        gym.make("chronocooked/FixedInterval-v0", td=0)
    with pytest.raises(ValueError, match=r"unknown parameter `speed`.*known"):
        gym.make("chronocooked/FixedInterval-v0", speed=3)
    with pytest.raises(ValueError, match="obs_mode"):
        gym.make("chronocooked/FixedInterval-v0", obs_mode="pixels")
    with pytest.raises(ValueError, match="render_mode"):
        chronocooked.ChronoEnv(render_mode="human")
    env = gym.make("chronocooked/FixedInterval-v0").unwrapped
    env.reset(seed=0)
    with pytest.raises(ValueError, match=r"invalid action 7 \(allowed"):
        env.step(7)
    with pytest.raises(ValueError, match="invalid action"):
        env.step(1.5)
    v = gym.make_vec("chronocooked/FixedInterval-v0", num_envs=2,
                     vectorization_mode="vector_entry_point")
    v.reset(seed=0)
    with pytest.raises(ValueError, match="exactly 2"):
        v.step(np.array([1, 2, 3]))
    with pytest.raises(ValueError, match="invalid action -1"):
        v.step(np.array([1, -1]))


def test_stepping_a_finished_episode_raises():
    env = chronocooked.ChronoEnv("FixedInterval-v0", max_timesteps=2)
    env.reset(seed=0)
    for _ in range(3):
        _, _, term, trunc, _ = env.step(0)
    assert term or trunc
    with pytest.raises(RuntimeError, match="call reset"):
        env.step(0)


def test_render_modes():
    env = gym.make("chronocooked/FixedInterval-v0", render_mode="rgb_array")
    env.reset(seed=0)
    img = env.render()
    assert img.dtype == np.uint8 and img.ndim == 3 and img.shape[2] == 3
    assert img.shape[:2] == (5 * 32, 3 * 32)
    text = gym.make("chronocooked/FixedInterval-v0", render_mode="ansi")
    text.reset(seed=0, options={"start": (1, 1)})
    assert "@" in text.render() and "V" in text.render()


def test_task_documentation_lists_parameters():
    tasks = {t["id"]: t for t in chronocooked.tasks()}
    keys = {p["key"] for p in tasks["Bisection-v0"]["params"]}
    assert {"short", "long", "max_timesteps", "reference_compat"} <= keys
    fi = {p["key"]: p for p in tasks["FixedInterval-v0"]["params"]}
    assert "oven_duration" in fi["td"]["aliases"]


def test_a_rust_panic_is_an_exception_not_an_abort():
    with pytest.raises(BaseException, match="deliberate panic"):
        chronocooked._core._panic_for_tests()
    env = gym.make("chronocooked/FixedInterval-v0")  # the interpreter and the module go on
    obs, _ = env.reset(seed=0)
    assert obs.shape == (5, 3, 6)


def test_step_before_reset_raises():
    env = gym.make("chronocooked/FixedInterval-v0")
    with pytest.raises(gym.error.ResetNeeded):
        env.step(0)
