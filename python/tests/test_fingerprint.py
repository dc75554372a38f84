"""`chronocooked.fingerprint`: two timing agents written here (not lab models) are named as
the mechanism they implement; agents without activity get the behavioural part; failures
leave nothing; `summarize` gives the neural summary of any evaluation folder."""

import json

import numpy as np
import pytest

import chronocooked
from conftest import ROOT
from policies import TimingOracle
from timing_agents import Accumulator, Mixed, OscillatorBank, TimeCellChain


def _distance(result, mechanism):
    return next(d for d in result["distances"] if d["mechanism"] == mechanism)


@pytest.mark.parametrize("seed", [0, 1])
@pytest.mark.parametrize(
    "agent, mechanism",
    [(Accumulator, "ddm"), (OscillatorBank, "sbf")],
    ids=["pacemaker-accumulator", "oscillator-bank"],
)
def test_a_timing_agent_is_named_as_the_mechanism_it_implements(tmp_path, agent, mechanism, seed):
    out = tmp_path / "fp"
    r = chronocooked.fingerprint(lambda task, params: agent(task, params, seed=seed), out,
                                 seed=seed, units_correspond=True, name=agent.__name__)
    assert r["nearest"] == mechanism, r["verdict"]
    assert r["distances"][0]["mechanism"] == mechanism
    # Every feature measured: behaviour, unit categories, scaling, decoding.
    assert r["missing"] == []
    # Every bootstrap resample of the mechanisms' seeds names the same mechanism.
    assert r["distances"][0]["bootstrap_share"] > 0.9, r["distances"]
    lo, hi = r["distances"][0]["self_range"]
    assert 0 <= lo <= hi
    # The files: one folder per condition, the card, and fingerprint.json last.
    for c in chronocooked.CONDITIONS:
        assert (out / c / "eval" / "metrics.json").is_file()
    for c in ("fi-td6", "fi-td12"):
        assert (out / c / "activity.summary.json").is_file()
    for f in ("fingerprint.md", "fingerprint.html", "fingerprint.png", "fingerprint.json"):
        assert (out / f).stat().st_size > 0
    saved = json.loads((out / "fingerprint.json").read_text())
    assert saved["units"]["nearest"] == mechanism
    assert "<h1>Fingerprint — " in (out / "fingerprint.html").read_text()


def test_signature_features_of_the_accumulator_are_those_of_a_ramp_that_scales(tmp_path):
    r = chronocooked.fingerprint(lambda task, params: Accumulator(task, params, seed=5),
                                 tmp_path / "fp", seed=8, units_correspond=True)
    s = r["signature"]
    assert s["frac_ramp"] == pytest.approx(1.0)
    assert s["frac_oscillating"] == 0
    # The drift is set by the interval: activity stretches with TD (index 1).
    assert s["scaling_index"] == pytest.approx(1.0, abs=0.2)
    # Scalar timing: the first-check CV follows the rate's CV 0.15 at both TDs.
    assert s["foc_cv"] == pytest.approx(0.15, abs=0.05)
    assert abs(s["foc_cv_trend"]) < 0.3


def test_an_agent_without_activity_gets_the_behavioural_part(tmp_path):
    def make(task, params):
        return TimingOracle(**params)

    r = chronocooked.fingerprint(make, tmp_path / "fp", draws=1)
    for f in ("frac_ramp", "frac_time_field", "frac_oscillating", "scaling_index",
              "decode_error_over_td"):
        assert f in r["missing"]
    # A deterministic timer: its first check never varies (CV 0); bisection is a step.
    assert r["signature"]["foc_cv"] == 0 and "bp_over_gm" in r["signature"]
    assert r["nearest"] is not None
    assert "No neural card" in (tmp_path / "fp" / "fingerprint.html").read_text()


def test_a_mapping_may_leave_conditions_out_and_their_features_are_missing(tmp_path):
    r = chronocooked.fingerprint({"fi-td12": Accumulator("FixedInterval-v0", {"td": 12})},
                                 tmp_path / "fp", draws=2)
    assert r["conditions"] == ["fi-td12"]
    assert {"wf", "bp_over_gm", "foc_cv_trend", "scaling_index"} <= set(r["missing"])
    assert not (tmp_path / "fp" / "fi-td6").exists()
    with pytest.raises(ValueError, match="fi-td6, fi-td12, bisection-4-12"):
        chronocooked.fingerprint({"fi-6": None}, tmp_path / "none")
    with pytest.raises(ValueError, match="make_policy"):
        chronocooked.fingerprint(42, tmp_path / "none")
    with pytest.raises(ValueError, match="draws"):
        chronocooked.fingerprint({"fi-td12": None}, tmp_path / "none", draws=0)


def test_a_failing_policy_names_the_condition_and_leaves_nothing(tmp_path):
    def make(task, params):
        if params.get("td") == 12:
            def broken(obs, state, episode_start):
                raise KeyError("no such unit")
            return broken
        return Accumulator(task, params)

    out = tmp_path / "fp"
    with pytest.raises(chronocooked.PolicyError) as err:
        chronocooked.fingerprint(make, out, draws=1)
    assert err.value.condition == "fi-td12"
    assert err.value.episode == 1 and err.value.step == 1
    assert isinstance(err.value.__cause__, KeyError)
    assert not out.exists()


def test_named_populations_are_recorded_and_summarized_from_an_evaluation_folder(tmp_path):
    base = Accumulator("FixedInterval-v0", {"td": 12})

    def policy(obs, state, episode_start):
        action, state, ramp = base(obs, state, episode_start)
        return action, state, {"ramp": ramp, "flip": -ramp[:3]}

    out = tmp_path / "eval"
    chronocooked.evaluate(policy, "FixedInterval-v0", out, td=12, name="two-pops")
    summaries = chronocooked.summarize(out, units_correspond=True)
    assert [s["population"] for s in summaries] == ["ramp", "flip"]
    assert [s["units"] for s in summaries] == [8, 3]
    for s in summaries:
        assert s["categories"]["counts"]["ramp"] == s["units"]
    assert (out / "activity.summary.json").is_file()
    arrays, meta = chronocooked.load_activity(out)
    assert arrays["activity"].shape[1] == 11
    with pytest.raises(ValueError, match="no activity dataset"):
        chronocooked.summarize(tmp_path)
    # Populations that change between steps are refused.
    flip = {"n": 0}

    def unstable(obs, state, episode_start):
        flip["n"] += 1
        pops = {"a": np.zeros(2)} if flip["n"] % 2 else {"b": np.zeros(2)}
        return 0, state, pops

    with pytest.raises(chronocooked.PolicyError, match="changed size"):
        chronocooked.evaluate(unstable, "FixedInterval-v0", tmp_path / "bad", td=6)


def _example_env(tmp_path):
    import os

    return dict(os.environ, PYTHONPATH=str(ROOT / "examples" / "python"),
                CHRONOCOOKED_CACHE=str(tmp_path / "cache"))


def test_the_worked_example_runs_as_written_in_under_a_minute(tmp_path):
    import subprocess
    import sys
    import time

    start = time.time()
    out = subprocess.run([sys.executable, str(ROOT / "examples/python/fingerprint_my_agent.py"),
                          str(tmp_path / "fp")], cwd=tmp_path, env=_example_env(tmp_path),
                         capture_output=True, text=True)
    seconds = time.time() - start
    assert out.returncode == 0, out.stderr
    assert seconds < 60, f"{seconds:.0f} s"
    for agent in ("pacemaker", "lstm125"):
        saved = json.loads((tmp_path / "fp" / agent / "fingerprint.json").read_text())
        assert saved["units"]["nearest"] in {"ddm", "sbf", "timecells-csc", "timecells-ms",
                                                 "timecells-laplace"}
    # The zoo agent has no TD-6 run: the trend and scaling features are missing.
    lstm = json.loads((tmp_path / "fp" / "lstm125" / "fingerprint.json").read_text())
    assert {"foc_cv_trend", "scaling_index"} <= set(lstm["units"]["missing"])
    assert out.stdout.count("distance") >= 10, out.stdout


def test_the_readme_fingerprint_block_runs_as_written(tmp_path):
    import re
    import subprocess
    import sys

    text = (ROOT / "docs" / "python.md").read_text()
    block = re.search(r"<!-- example: fingerprint -->\s*```python\n(.*?)```", text, re.S)
    assert block, "docs/python.md has the fingerprint example"
    out = subprocess.run([sys.executable, "-c", block.group(1)], cwd=tmp_path,
                         env=_example_env(tmp_path), capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert (tmp_path / "lab-out" / "fp-mine" / "fingerprint.json").is_file()
    assert "my-pacemaker" in out.stdout


@pytest.mark.parametrize(
    "agent", [Accumulator, OscillatorBank, TimeCellChain],
    ids=["ramps", "oscillator-bank", "time-cell-chain"],
)
def test_the_dynamics_view_gives_the_same_verdict_in_any_orthogonal_basis(tmp_path, agent):
    """The same agent seen through a fixed random orthogonal mixing of its units (the same
    dynamics in another basis): the dynamics view's distances and verdict do not move; the
    unit view of the oscillator bank does (a documented fact of single-unit categories)."""
    plain = chronocooked.fingerprint(lambda task, params: agent(task, params, seed=3),
                                     tmp_path / "plain", seed=3, units_correspond=True)
    mixed = chronocooked.fingerprint(lambda task, params: Mixed(agent(task, params, seed=3)),
                                     tmp_path / "mixed", seed=3, units_correspond=True)
    a, b = plain["dynamics"], mixed["dynamics"]
    assert (a["nearest"], a["identified"]) == (b["nearest"], b["identified"]), (a, b)
    for x, y in zip(a["distances"], b["distances"]):
        assert x["mechanism"] == y["mechanism"]
        assert x["distance"] == pytest.approx(y["distance"], rel=1e-4, abs=1e-4)
    # Two fingerprints of one agent's dynamics are at distance 0 on the mechanisms' scale.
    assert chronocooked.distance(tmp_path / "plain", tmp_path / "mixed") == pytest.approx(0, abs=1e-3)
    if agent is OscillatorBank:
        assert plain["signature"]["frac_oscillating"] > 0.9
        assert mixed["signature"]["frac_oscillating"] < plain["signature"]["frac_oscillating"] - 0.2
        assert plain["nearest"] == "sbf"


def test_distance_refuses_an_unknown_view_and_a_folder_without_a_fingerprint(tmp_path):
    with pytest.raises(ValueError, match="allowed"):
        chronocooked.distance(tmp_path, tmp_path, view="cells")
    with pytest.raises(ValueError, match="fingerprint.json"):
        chronocooked.distance(tmp_path, tmp_path)
