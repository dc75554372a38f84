"""`chronocooked.record` (a Python policy's activity on probe trials, with its export and
neural summary) and the study commands from Python (`analyse`, `mechanisms`), which must
write what the CLI writes."""

import shutil
import subprocess

import pytest

import chronocooked
from conftest import ROOT
from policies import TimingOracle
from timing_agents import Accumulator, OscillatorBank


def _counts(summary):
    (pop,) = summary
    return pop["categories"]["counts"], pop["units"]


@pytest.mark.parametrize("td", [7, 15])
def test_an_accumulator_recorded_on_probe_trials_is_eight_ramps(tmp_path, td):
    out = tmp_path / "rec"
    r = chronocooked.record(Accumulator("FixedInterval-v0", {"td": td}, seed=td),
                            "FixedInterval-v0", out, td=td, seed=td)
    assert r["task"] == "PeakInterval-v0" and r["tds"] == [td]
    counts, units = _counts(r["summary"])
    # Eight gains x one ramp per trial: every unit a ramp.
    assert units == 8
    assert counts["ramp"] == 8, counts
    # The files: the dataset, its NPZ export and the summary (written last).
    for f in ("activity.json", "activity.summary.json", "activity/activity.npz"):
        assert (out / f).is_file(), f
    arrays, meta = chronocooked.load_activity(out)
    assert meta["model"] == "python-policy"
    # Probe trials: the soup is withheld, so every aligned trial spans 2 x TD after oven-on.
    assert arrays["aligned"].shape[0] == r["trials"]
    assert arrays["aligned"].shape[1] >= 2 * td
    assert arrays["aligned"].shape[2] == 8


def test_an_oscillator_bank_is_oscillating_and_repeats_add_trials(tmp_path):
    once = chronocooked.record(OscillatorBank("FixedInterval-v0", {"td": 10}, seed=1),
                               "FixedInterval-v0", tmp_path / "a", td=10, seed=4)
    twice = chronocooked.record(OscillatorBank("FixedInterval-v0", {"td": 10}, seed=1),
                                "FixedInterval-v0", tmp_path / "b", td=10, seed=4, repeats=2)
    assert twice["trials"] == 2 * once["trials"]
    counts, units = _counts(twice["summary"])
    assert units == 64
    assert counts["oscillating"] >= 0.9 * units, counts
    assert counts["untuned"] == 0, counts


def test_record_without_probe_plays_the_task_itself_at_its_evaluation_tds(tmp_path):
    r = chronocooked.record(Accumulator("Bisection-v0", {"short": 4, "long": 12}),
                            "Bisection-v0", tmp_path / "bis", probe=False, short=4, long=12,
                            summary=False)
    assert r["task"] == "Bisection-v0" and r["tds"] == [4, 12]
    assert "summary" not in r
    assert not (tmp_path / "bis" / "activity.summary.json").exists()
    assert (tmp_path / "bis" / "activity.json").is_file()


def test_bad_requests_and_failing_policies_write_nothing(tmp_path):
    out = tmp_path / "nothing"
    with pytest.raises(ValueError, match="probe"):
        chronocooked.record(Accumulator("Bisection-v0", {"short": 4, "long": 12}),
                            "Bisection-v0", out)
    with pytest.raises(ValueError, match="repeats"):
        chronocooked.record(Accumulator("FixedInterval-v0", {"td": 6}), "FixedInterval-v0",
                            out, repeats=0)
    # A policy without activity has nothing to record.
    with pytest.raises(ValueError, match="no activity"):
        chronocooked.record(TimingOracle(td=6), "FixedInterval-v0", out, td=6)

    class Breaks(Accumulator):
        def __call__(self, obs, state, episode_start):
            self.steps = getattr(self, "steps", 0) + 1
            if self.steps == 30:
                raise ZeroDivisionError("boom")
            return super().__call__(obs, state, episode_start)

    with pytest.raises(chronocooked.PolicyError) as e:
        chronocooked.record(Breaks("FixedInterval-v0", {"td": 6}), "FixedInterval-v0", out,
                            td=6)
    assert isinstance(e.value.__cause__, ZeroDivisionError)
    assert e.value.episode >= 1 and e.value.step >= 1
    assert not out.exists()


def test_mechanisms_from_python_writes_what_the_cli_writes(tmp_path, cli):
    study = ROOT / "results" / "mechanisms-reference"
    r = chronocooked.mechanisms(study, tmp_path / "py", seed=3)
    subprocess.run([cli, "mechanisms", str(study), "--out", str(tmp_path / "cli"),
                    "--seed", "3"], check=True, capture_output=True)
    for f in ("signatures.csv", "mechanisms.csv", "mechanisms.md"):
        assert (tmp_path / "py" / f).read_bytes() == (tmp_path / "cli" / f).read_bytes(), f
    # Every mechanism seed (not the PPO agents' seeds) is held out once and named (or not)
    # in the result.
    rows = (tmp_path / "py" / "signatures.csv").read_text().splitlines()[1:]
    assert r["signatures"] == len(rows)
    expected = {"ddm", "sbf", "timecells-csc", "timecells-ms", "timecells-laplace"}
    assert len(r["held_out"]) == sum(row.split(",")[0] in expected for row in rows)
    mechanisms = {h["mechanism"] for h in r["held_out"]}
    assert mechanisms == expected
    assert all(h["named"] in mechanisms for h in r["held_out"])
    assert all(0 <= h["self_distance"] for h in r["held_out"])
    with pytest.raises(ValueError, match="no finished jobs"):
        chronocooked.mechanisms(tmp_path / "py", tmp_path / "empty")


def test_paper_analyse_from_python_writes_what_the_cli_writes(tmp_path, cli):
    study = ROOT / "results" / "paper-core-lab-init"
    # One folder name (the tables name their folder), two parents.
    a, b = tmp_path / "py" / "study", tmp_path / "cli" / "study"
    for d in (a, b):
        shutil.copytree(study / "jobs", d / "jobs")
    r = chronocooked.analyse(a)
    done = subprocess.run([cli, "paper", "analyse", str(b)], check=True, capture_output=True,
                          text=True)
    assert done.stdout.startswith(f"{r['jobs']} jobs analysed")
    for f in ("tables.md", "comparison.csv", "agreement.json"):
        assert (a / f).read_bytes() == (b / f).read_bytes(), f
    assert (a / "report.html").is_file() and r["report"].name == "report.html"
    assert r["figures"] and all(str(p).startswith(str(a)) for p in r["figures"])
    with pytest.raises(OSError):
        chronocooked.analyse(tmp_path / "missing")


def test_export_from_python_writes_what_the_cli_writes_and_a_bad_input_keeps_it(tmp_path, cli):
    ev = tmp_path / "ev"
    chronocooked.evaluate(Accumulator("FixedInterval-v0", {"td": 6}, seed=2), "FixedInterval-v0",
                          ev, td=6, seed=2)
    py, c = tmp_path / "py" / "x", tmp_path / "cli" / "x"
    files = chronocooked.export(py, activity=ev, eval=ev, window=30)
    assert files[-1].name == "export.json"
    subprocess.run([cli, "export", "--activity", str(ev / "activity.json"), "--eval", str(ev),
                    "--window", "30", "--out", str(c)], check=True, capture_output=True)
    names = sorted(p.name for p in py.iterdir())
    assert names == sorted(p.name for p in c.iterdir())
    assert {"activity.npz", "episodes.npz", "export.json"} <= set(names)
    for n in names:
        if n != "SHA256SUMS":
            assert (py / n).read_bytes() == (c / n).read_bytes(), n
    chronocooked.check_export(py)
    arrays, _ = chronocooked.load_activity(py)
    assert arrays["aligned"].shape[1] <= 30
    # Bad requests: nothing to export, a folder that is no evaluation; the export stays whole.
    with pytest.raises(ValueError, match="say what to export"):
        chronocooked.export(py)
    with pytest.raises(ValueError, match="not an evaluation folder"):
        chronocooked.export(py, eval=tmp_path / "py")
    chronocooked.check_export(py)
