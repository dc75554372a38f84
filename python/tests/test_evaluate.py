"""evaluate() with Python policies: the same evaluation folder as `chronocooked eval`, a
leaderboard row in `chronocooked report`, readers, activity and the NWB export."""

import json
import subprocess

import numpy as np
import pytest

import chronocooked
from policies import TimingOracle


def _cli_eval(cli, out, task, *env):
    args = [cli, "eval", "--agent", "oracle", "--task", task, "--out", str(out)]
    for e in env:
        args += ["--env", e]
    subprocess.run(args, check=True, capture_output=True)


@pytest.mark.parametrize("task,params,policy", [
    ("FixedInterval-v0", {"td": 9}, lambda: TimingOracle(td=9)),
    ("Bisection-v0", {"short": 4, "long": 12}, lambda: TimingOracle(short=4, long=12)),
])
def test_python_oracle_gives_the_metrics_of_the_cli_oracle(tmp_path, cli, task, params, policy):
    py = tmp_path / "py"
    summary = chronocooked.evaluate(policy(), task, py, name="oracle", **params)
    _cli_eval(cli, tmp_path / "rs", task, *[f"{k}={v}" for k, v in params.items()])
    assert json.loads((py / "metrics.json").read_text()) == json.loads(
        (tmp_path / "rs" / "metrics.json").read_text())
    # The same episodes, step for step (same conditions, start cells and seeds).
    assert (py / "records.jsonl").read_text() == (tmp_path / "rs" / "records.jsonl").read_text()
    assert json.loads((py / "eval.json").read_text()) == json.loads(
        (tmp_path / "rs" / "eval.json").read_text())
    assert summary["episodes"] > 30 and (py / "figures").is_dir()


def test_an_evaluated_policy_is_a_leaderboard_row(tmp_path, cli):
    chronocooked.evaluate(TimingOracle(td=12), "FixedInterval-v0", tmp_path / "mine",
                          name="my-python-agent")
    subprocess.run([cli, "eval", "--agent", "random", "--task", "FixedInterval-v0",
                    "--out", str(tmp_path / "random")], check=True, capture_output=True)
    subprocess.run([cli, "report", "--eval", str(tmp_path / "mine"), str(tmp_path / "random"),
                    "--out", str(tmp_path / "report")], check=True, capture_output=True)
    html = (tmp_path / "report" / "report.html").read_text()
    csv = (tmp_path / "report" / "report.csv").read_text()
    assert "my-python-agent" in html and "my-python-agent" in csv
    row = [line for line in csv.splitlines() if line.startswith("my-python-agent")]
    assert row, csv


def test_model_names_with_commas_stay_one_csv_field(tmp_path, cli):
    import csv as csvmod

    name = 'agent, "v2"'
    chronocooked.evaluate(TimingOracle(td=12), "FixedInterval-v0", tmp_path / "a", name=name)
    subprocess.run([cli, "report", "--eval", str(tmp_path / "a"), "--out", str(tmp_path / "r")],
                   check=True, capture_output=True)
    with open(tmp_path / "r" / "report.csv", newline="") as f:
        rows = list(csvmod.reader(f))
    assert rows[1][0] == name and len(rows[1]) == len(rows[0])


def test_load_eval_returns_episode_and_condition_frames(tmp_path):
    chronocooked.evaluate(TimingOracle(td=6), "FixedInterval-v0", tmp_path, td=6)
    episodes, conditions = chronocooked.load_eval(tmp_path)
    # 12 free cells × (FI + two PI probes)
    assert len(episodes) == 36 and set(episodes["kind"]) == {"fi", "pi"}
    fi = episodes[episodes["kind"] == "fi"]
    assert fi["success"].all() and (fi["first_check"] == 6).all()
    assert (fi["oven_off_time"] == 6).all() and (fi["counter"] == "main").all()
    assert list(conditions["kind"]) == ["fi", "pi", "pi"]
    assert conditions.loc[0, "success_rate"] == 1.0


def test_activity_is_recorded_exported_and_written_to_nwb(tmp_path):
    from nwbinspector import Importance, inspect_nwbfile
    from pynwb import NWBHDF5IO

    out = tmp_path / "ev"
    s = chronocooked.evaluate(TimingOracle(td=6, activity=True), "FixedInterval-v0", out,
                              name="py-ramp", td=6)
    assert s["units"] == 3
    arrays, meta = chronocooked.load_activity(out / "activity")
    assert meta["model"] == "py-ramp" and meta["units"] == ["units[0]", "units[1]", "units[2]"]
    act, offsets = arrays["activity"], arrays["trial_offsets"]
    assert act.shape == (offsets[-1], 3) and len(offsets) == 37
    # The policy's counter ramps from the onion-in step: in the 12 FI trials unit 0 reaches
    # TD at the pickup; in the peak-interval probes it goes on to the release at 2 and 5 TD.
    assert act[: offsets[12], 0].max() == 6.0 and act[:, 0].max() == 30.0
    path = chronocooked.to_nwb(out / "activity", out, tmp_path / "run.nwb")
    messages = list(inspect_nwbfile(nwbfile_path=str(path)))
    bad = [m for m in messages
           if m.importance in (Importance.CRITICAL, Importance.BEST_PRACTICE_VIOLATION)]
    assert not bad, [(m.check_function_name, m.message) for m in bad]
    records = [json.loads(x) for x in (out / "records.jsonl").read_text().splitlines()]
    with NWBHDF5IO(str(path), "r") as io:
        nwb = io.read()
        ts = nwb.processing["model"]["unit_activity"]
        np.testing.assert_array_equal(ts.data[:], arrays["activity"])
        assert ts.rate == 1.0
        trials = nwb.trials.to_dataframe()
        np.testing.assert_array_equal(trials["td"].to_numpy(), arrays["td"])
        np.testing.assert_array_equal(trials[["start_row", "start_col"]].to_numpy(),
                                      arrays["start"])
        np.testing.assert_array_equal(trials["reward"].to_numpy(), arrays["reward"])
        np.testing.assert_array_equal(trials["success"].to_numpy().astype(np.int64),
                                      np.asarray(arrays["success"]).astype(np.int64))
        np.testing.assert_array_equal(trials["start_time"].to_numpy(), offsets[:-1])
        np.testing.assert_array_equal(trials["stop_time"].to_numpy(), offsets[1:])
        ev = nwb.events["task_events"].to_dataframe()
        np.testing.assert_array_equal(ev["trial"].to_numpy(), arrays["event_trial"])
        np.testing.assert_array_equal(ev["step"].to_numpy(), arrays["event_step"])
        np.testing.assert_array_equal(
            ev["timestamp"].to_numpy(),
            offsets[arrays["event_trial"]] + arrays["event_step"])
        names = [meta["event_codes"][str(c)] for c in arrays["event_code"]]
        assert list(ev["event"]) == names
        pos = nwb.processing["behavior"]["Position"]["agent_position"].data[:]
        np.testing.assert_array_equal(
            pos, [i["agent"] for r in records for i in r["episode"]["infos"]])
        actions = nwb.processing["behavior"]["actions"]["action"].data[:]
        np.testing.assert_array_equal(actions, [a for r in records for a in r["episode"]["actions"]])
        assert "py-ramp" in nwb.session_id and '"seed": 0' in nwb.notes
    with pytest.raises(FileExistsError):
        chronocooked.to_nwb(out / "activity", out, path)


def test_an_agent_that_never_acts_on_the_task_still_gets_an_nwb_file(tmp_path):
    # Waiting in place all episode: no task event at all (a barely trained agent does this).
    from pynwb import NWBHDF5IO

    def wait(obs, state, episode_start):
        return 0, state, np.array([1.0 if episode_start else 0.0, 0.5], np.float32)

    out = tmp_path / "idle"
    chronocooked.evaluate(wait, "FixedInterval-v0", out, td=6)
    arrays, _ = chronocooked.load_activity(out / "activity")
    assert len(arrays["event_code"]) == 0
    path = chronocooked.to_nwb(out / "activity", out, tmp_path / "idle.nwb")
    with NWBHDF5IO(str(path), "r") as io:
        nwb = io.read()
        assert len(nwb.events["task_events"].to_dataframe()) == 0
        assert nwb.processing["model"]["unit_activity"].data.shape[1] == 2
        assert len(nwb.trials) == len(arrays["td"])


def test_an_interrupted_or_mixed_export_is_refused(tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    chronocooked.evaluate(TimingOracle(td=6, activity=True), "FixedInterval-v0", a, td=6)
    chronocooked.evaluate(TimingOracle(td=9, activity=True), "FixedInterval-v0", b, td=9)
    marker = json.loads((a / "activity" / "export.json").read_text())
    assert {f["name"] for f in marker["files"]} >= {"activity.npz", "activity.meta.json"}
    # A file of another export in the folder: the sizes or hashes differ.
    (a / "activity" / "activity.npz").write_bytes((b / "activity" / "activity.npz").read_bytes())
    with pytest.raises(ValueError, match=r"activity\.npz.*differs"):
        chronocooked.load_activity(a / "activity")
    # No marker: an export cut short before its last file.
    (b / "activity" / "export.json").unlink()
    with pytest.raises(FileNotFoundError, match="incomplete"):
        chronocooked.load_activity(b / "activity")


def test_nwb_refuses_activity_from_another_run(tmp_path):
    a = tmp_path / "a"
    b = tmp_path / "b"
    chronocooked.evaluate(TimingOracle(td=6, activity=True), "FixedInterval-v0", a, td=6)
    chronocooked.evaluate(TimingOracle(short=4, long=12), "Bisection-v0", b, short=4, long=12)
    with pytest.raises(ValueError, match="not from the same run"):
        chronocooked.to_nwb(a / "activity", b, tmp_path / "x.nwb")


def test_stochastic_protocol_plays_n_episodes_per_condition(tmp_path):
    s = chronocooked.evaluate(TimingOracle(td=12), "FixedInterval-v0", tmp_path, stochastic=5)
    assert s["episodes"] == 15
    info = json.loads((tmp_path / "eval.json").read_text())
    assert info["mode"] == {"Stochastic": {"episodes": 5}}


def test_onehot_observations_reach_the_policy(tmp_path):
    shapes = set()

    def policy(obs, state, start):
        shapes.add((obs.dtype, obs.shape))
        return 0, state

    chronocooked.evaluate(policy, "FixedInterval-v0", tmp_path, obs_mode="onehot", stochastic=1)
    (dtype, shape), = shapes
    assert dtype == np.float32 and shape[1:] == (5, 3)


def test_policy_errors_surface_as_python_exceptions(tmp_path):
    def boom(obs, state, start):
        raise KeyError("my bug")

    with pytest.raises(chronocooked.PolicyError, match="my bug") as e:
        chronocooked.evaluate(boom, "FixedInterval-v0", tmp_path / "a")
    assert isinstance(e.value.__cause__, KeyError)
    assert (e.value.episode, e.value.step) == (1, 1)
    assert e.value.task == "FixedInterval-v0" and e.value.td > 0

    def late(obs, state, start):
        # Fails at the third step of the second episode.
        n = 0 if start else state
        episodes = getattr(late, "episodes", 0) + (1 if start else 0)
        late.episodes = episodes
        if episodes == 2 and n == 2:
            raise RuntimeError("late bug")
        return 0, n + 1

    with pytest.raises(chronocooked.PolicyError, match=r"episode 2 .*step 3: late bug") as e:
        chronocooked.evaluate(late, "FixedInterval-v0", tmp_path / "late")
    assert (e.value.episode, e.value.step) == (2, 3)
    bad_outputs = [
        (lambda o, s, e: (9, s), r"invalid action 9 \(allowed"),
        (lambda o, s, e: (1.5, s), "must be an integer"),
        (lambda o, s, e: ("left", s), "must be an integer"),
        (lambda o, s, e: (1,), "returned 1 values"),
        (lambda o, s, e: (0, (s or 0) + 1, np.zeros((s or 0) + 1)), "changed size"),
        (lambda o, s, e: (0, s, np.array([0.0, np.nan])), "NaN at unit 1"),
        (lambda o, s, e: (0, s, np.array([np.inf])), "inf at unit 0"),
    ]
    for k, (policy, message) in enumerate(bad_outputs):
        out = tmp_path / f"bad{k}"
        with pytest.raises(chronocooked.PolicyError, match=message) as e:
            chronocooked.evaluate(policy, "FixedInterval-v0", out)
        assert e.value.episode >= 1 and e.value.step >= 1
        # Nothing is written: no half-written evaluation folder.
        assert not out.exists()
    with pytest.raises(ValueError, match="callable"):
        chronocooked.evaluate(3, "FixedInterval-v0", tmp_path / "e")
    with pytest.raises(ValueError, match=r"`td`.*allowed"):
        chronocooked.evaluate(lambda o, s, e: (0, s), "FixedInterval-v0", tmp_path / "f", td=0)
    with pytest.raises(ValueError, match="stochastic"):
        chronocooked.evaluate(lambda o, s, e: (0, s), "FixedInterval-v0", tmp_path / "g",
                              stochastic=0)
    assert not (tmp_path / "a").exists()


def test_numpy_actions_and_states_pass_through(tmp_path):
    def policy(obs, state, start):
        state = np.zeros(4) if start else state + 1
        return np.int64(0), state, state

    s = chronocooked.evaluate(policy, "FixedInterval-v0", tmp_path, stochastic=1)
    arrays, _ = chronocooked.load_activity(tmp_path)
    assert s["units"] == 4 and arrays["activity"][1, 0] == 1.0


def test_cli_export_writes_nwb_through_the_package(tmp_path, cli):
    import sys

    from pynwb import NWBHDF5IO

    ev = tmp_path / "ev"
    chronocooked.evaluate(TimingOracle(td=9, activity=True), "FixedInterval-v0", ev, td=9)
    out = tmp_path / "export"
    done = subprocess.run([cli, "export", "--activity", str(ev / "activity.json"), "--eval",
                           str(ev), "--format", "nwb", "--python", sys.executable, "--out",
                           str(out)], check=True, capture_output=True, text=True)
    assert str(out / "run.nwb") in done.stdout
    with NWBHDF5IO(str(out / "run.nwb"), "r") as io:
        nwb = io.read()
        assert nwb.processing["model"]["unit_activity"].data.shape[1] == 3
        assert len(nwb.trials) == 36
    missing = subprocess.run([cli, "export", "--activity", str(ev / "activity.json"), "--eval",
                              str(ev), "--format", "nwb", "--python", str(tmp_path / "nopython"),
                              "--out", str(tmp_path / "x")], capture_output=True, text=True)
    assert missing.returncode != 0 and "pip install" in missing.stderr
