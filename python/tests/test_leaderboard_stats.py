"""Few-run statistics from Python: the IQM and its stratified bootstrap interval, the
probability of improvement, and the leaderboard's pairwise table — against values worked
out by hand."""

import csv

import pytest

import chronocooked
from policies import TimingOracle


def test_probability_of_improvement_counts_pairs_with_ties_as_halves():
    # 1 beats 0; 2 ties 2 twice and beats 0; 3 beats all: 1 + 2 + 3 = 6 of 9 pairs.
    assert chronocooked.probability_of_improvement([1, 2, 3], [2, 2, 0]) == pytest.approx(6 / 9)
    assert chronocooked.probability_of_improvement([1, 2], [1, 2]) == 0.5


def test_iqm_and_a_stratified_interval_by_hand():
    value, ci = chronocooked.iqm([100, 2, 1, 4, 3])
    assert value == 3.0 and ci[0] <= 3.0 <= ci[1]
    # Every resample keeps three 0s (stratum a) and three 10s (b): the IQM is always 5.
    value, ci = chronocooked.iqm([0, 0, 0, 10, 10, 10], strata=list("aaabbb"))
    assert value == 5.0 and ci == (5.0, 5.0)
    assert chronocooked.iqm([1.0])[1] is None
    with pytest.raises(ValueError, match="one label per value"):
        chronocooked.iqm([1, 2], strata=["a"])


def test_the_leaderboard_writes_iqm_columns_and_the_pairwise_table(tmp_path):
    evals = []
    for name, td in (("exact-a", 6), ("exact-b", 6)):
        out = tmp_path / name
        chronocooked.evaluate(TimingOracle(td=td), "FixedInterval-v0", out, td=td, name=name)
        evals.append(out)
    files = chronocooked.report(evals, tmp_path / "report", baselines=False,
                                improvement="foc_over_td")
    names = {f.name for f in files}
    assert {"report.csv", "improvement.csv", "improvement.md"} <= names
    header = (tmp_path / "report" / "report.csv").read_text().splitlines()[0].split(",")
    assert {"foc_over_td_iqm", "foc_over_td_iqm_lo", "foc_over_td_iqm_hi"} <= set(header)
    rows = list(csv.reader((tmp_path / "report" / "improvement.csv").read_text().splitlines()))
    assert rows[0] == ["row", "exact-a", "exact-b"]
    # Two exact timers: equal values, every pair a tie.
    assert [float(v) for v in rows[1][1:]] == [0.5, 0.5]
    with pytest.raises(ValueError, match="two are needed"):
        chronocooked.report(evals[:1], tmp_path / "r1", baselines=False,
                            improvement="foc_over_td")


def test_a_sweep_is_collected_from_python_and_becomes_a_baseline(tmp_path, cli):
    import subprocess

    sweep = tmp_path / "tiny.toml"
    # The oracle is deterministic (one job); drift-diffusion trains in a second per seed.
    sweep.write_text('name = "tiny"\ntasks = ["FixedInterval-v0"]\nmodels = ["oracle", "ddm"]\n'
                     'seeds = [0, 1]\nrecord = false\nexport = false\n')
    subprocess.run([cli, "sweep", str(sweep), "--out", str(tmp_path / "out"), "--workers", "1",
                    "--no-report"], check=True, capture_output=True)
    written, unfinished = chronocooked.collect(tmp_path / "out", tmp_path / "results")
    assert (written, unfinished) == (3, 0)
    jobs = sorted(f"{p.parent.parent.name}/{p.parent.name}"
                  for p in (tmp_path / "results").rglob("metrics.json"))
    assert jobs == ["ddm/seed0", "ddm/seed1", "oracle/seed0"]
    files = chronocooked.report([], tmp_path / "report", baselines=tmp_path / "results")
    rows = (tmp_path / "report" / "report.csv").read_text().splitlines()
    assert sorted(r.split(",")[0] for r in rows[1:]) == ["ddm (results)", "oracle (results)"]
    assert any(f.name == "report.html" for f in files)
    with pytest.raises(OSError, match="no such sweep output folder"):
        chronocooked.collect(tmp_path / "missing", tmp_path / "r2")
