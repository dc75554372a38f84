"""`chronocooked.sb3`: SB3 models as lab policies — the adapter's logic against a numpy
stand-in with SB3's contract (always), and a real RecurrentPPO trained for a few thousand
steps where stable-baselines3 and sb3-contrib are installed (marker `sb3`)."""

import json

import numpy as np
import pytest

import chronocooked
from chronocooked import sb3
from sb3_stand_in import StandInModel


def _activity(folder):
    d = json.loads((folder / "activity.json").read_text())
    names = [(p["name"], p["size"]) for p in d["meta"]["populations"]]
    width = sum(n for _, n in names)
    trials = [np.asarray(t["activity"], dtype=float).reshape(-1, width) for t in d["trials"]]
    return names, trials


def test_recurrent_states_are_recorded_as_named_populations_and_reset_at_episode_starts(tmp_path):
    model = StandInModel()
    policy = sb3.policy(model)
    assert policy.obs_mode == "codes" and policy.recurrent
    chronocooked.evaluate(policy, "FixedInterval-v0", tmp_path / "e", td=6, name="stand-in")
    names, trials = _activity(tmp_path / "e")
    assert names == [("features", 4), ("latent_pi", 2), ("hidden", 3), ("cell", 3)]
    cell = slice(9, 12)
    for t in trials:
        # The cell counts steps since the episode start: 1, 2, 3, … in every trial, so
        # the state was reset at each episode's first step.
        steps = np.arange(1, len(t) + 1)
        assert np.array_equal(t[:, cell][:, 0], steps)
    assert all(model.calls), "deterministic actions by default"


def test_a_feed_forward_model_records_its_features_and_the_hooks_come_off(tmp_path):
    model = StandInModel(recurrent=False)
    policy = sb3.policy(model, deterministic=False)
    chronocooked.evaluate(policy, "FixedInterval-v0", tmp_path / "e", td=6)
    names, _ = _activity(tmp_path / "e")
    assert names == [("features", 4), ("latent_pi", 2)]
    assert not any(model.calls)
    policy.close()
    assert model.policy.features_extractor.hooks == []
    # Without recording: no activity at all.
    chronocooked.evaluate(sb3.policy(StandInModel(), record=False), "FixedInterval-v0",
                          tmp_path / "quiet", td=6)
    assert not (tmp_path / "quiet" / "activity.json").exists()


def test_models_that_are_not_sb3_or_not_on_a_lab_env_are_refused_clearly():
    with pytest.raises(TypeError, match="Stable-Baselines3 model"):
        sb3.policy(object())
    with pytest.raises(ValueError, match="neither the lab's code observation"):
        sb3.policy(StandInModel(obs_shape=(4,)))
    with pytest.raises(ValueError, match="algo"):
        pytest.importorskip("stable_baselines3")
        sb3.load("x", algo="DQN")


def test_load_says_what_to_install_without_sb3(monkeypatch):
    import builtins

    real = builtins.__import__

    def no_sb3(name, *args, **kwargs):
        if name.startswith(("stable_baselines3", "sb3_contrib")):
            raise ImportError(name)
        return real(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_sb3)
    with pytest.raises(ImportError, match="pip install stable-baselines3 sb3-contrib"):
        sb3.load("model.zip")


@pytest.mark.sb3
def test_a_recurrent_ppo_trained_on_the_lab_env_is_evaluated_recorded_and_fingerprinted(tmp_path):
    pytest.importorskip("sb3_contrib")
    import gymnasium as gym
    from sb3_contrib import RecurrentPPO

    env = gym.make("chronocooked/FixedInterval-v0", td=6)
    model = RecurrentPPO("MlpLstmPolicy", env, n_steps=256, batch_size=64, seed=0,
                         policy_kwargs={"lstm_hidden_size": 16}, device="cpu")
    model.learn(2048)
    model.save(tmp_path / "rppo")
    policy = sb3.load(tmp_path / "rppo", algo="RecurrentPPO")
    out = tmp_path / "eval"
    chronocooked.evaluate(policy, "FixedInterval-v0", out, td=6, name="rppo")
    names, trials = _activity(out)
    assert ("hidden", 16) in names and ("cell", 16) in names
    # The NPZ export written by evaluate holds every population's units.
    arrays, meta = chronocooked.load_activity(out)
    assert arrays["activity"].shape[1] == sum(n for _, n in names)
    assert {"hidden", "cell"} <= {p["name"] for p in meta["populations"]}
    try:
        from pynwb import NWBHDF5IO
    except ImportError:
        NWBHDF5IO = None
    if NWBHDF5IO is not None:  # the NWB export, where pynwb is installed
        path = chronocooked.to_nwb(out / "activity", out, tmp_path / "rppo.nwb")
        with NWBHDF5IO(str(path), "r") as io:
            ts = io.read().processing["model"]["unit_activity"]
            assert ts.data.shape[1] == sum(n for _, n in names)
            assert '"hidden[15]"' in ts.comments and '"cell[15]"' in ts.comments
    r = chronocooked.fingerprint({"fi-td6": policy}, tmp_path / "fp", draws=1)
    assert r["conditions"] == ["fi-td6"]
    assert (tmp_path / "fp" / "fingerprint.json").is_file()
    # 2,048 steps rarely teach the task: an agent that never turns the oven on has no
    # timing features at all (and says so); one that does is placed.
    assert (r["nearest"] is not None) == bool(r["signature"]), r
