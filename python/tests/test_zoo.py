"""The zoo of trained agents and the leaderboard with committed baselines, from Python; the
the guide's worked example (docs/your-agent.md), run as written."""

import json
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import chronocooked
from conftest import ROOT


def test_the_zoo_lists_the_paper_agents_and_the_memory_control_with_provenance():
    agents = chronocooked.zoo.agents()
    names = sorted(a["name"] for a in agents)
    paper = [f"zoo:{m}/{t}" for m in ("cnn-mlp", "lstm125", "ctrnn125", "ctrnn-reservoir125")
             for t in ("FixedInterval-v0", "Bisection-v0")]
    # The frame-stack control (4 stacked frames, fixed interval at TD 4; issue #67).
    assert names == sorted(paper + ["zoo:cnn-mlp-stack4/FixedInterval-v0"])
    for a in agents:
        p = a["provenance"]
        control = a["name"] == "zoo:cnn-mlp-stack4/FixedInterval-v0"
        assert p["seed"] == (1 if control else 4)
        assert p["preset"] == "reference" and len(p["commit"]) == 40
        assert p["reproduces_study_job"] is True
    assert sum(a["bytes"] for a in agents) < 4_000_000


def test_a_zoo_policy_evaluates_to_its_recorded_success_and_records_its_activity(tmp_path):
    policy = chronocooked.zoo.load("zoo:ctrnn125/FixedInterval-v0")
    prov = chronocooked.zoo.provenance(policy)
    chronocooked.evaluate(policy, "FixedInterval-v0", tmp_path, td=12, name="zoo-ctrnn125")
    metrics = json.loads((tmp_path / "metrics.json").read_text())
    got = [c["success_rate"] for c in metrics["conditions"]]
    assert got == [c[3] for c in prov["evaluation"]["conditions"]]
    arrays, meta = chronocooked.load_activity(tmp_path)
    assert arrays["activity"].shape[1] == 125          # the CTRNN's latent population
    assert np.isfinite(arrays["activity"]).all() and arrays["activity"].std() > 0


def test_a_corrupt_zoo_file_raises_value_error_naming_it(tmp_path, monkeypatch):
    name = "cnn-mlp/FixedInterval-v0"
    shutil.copytree(ROOT / "zoo" / name, tmp_path / "zoo" / name)
    (tmp_path / "zoo" / "index.json").write_text(json.dumps({"format": 1, "agents": [name]}))
    monkeypatch.setenv("CHRONOCOOKED_ZOO", str(tmp_path / "zoo"))
    chronocooked.zoo.load(name)  # intact copy
    model = tmp_path / "zoo" / name / "model.bpk"
    data = bytearray(model.read_bytes())
    data[len(data) // 2] ^= 0xFF
    model.write_bytes(bytes(data))
    with pytest.raises(ValueError, match=r"model\.bpk.*does not match"):
        chronocooked.zoo.load(name)
    with pytest.raises(ValueError, match="no zoo agent `nope/FixedInterval-v0`"):
        chronocooked.zoo.load("nope/FixedInterval-v0")


def test_report_adds_the_committed_baselines(tmp_path):
    from policies import TimingOracle

    chronocooked.evaluate(TimingOracle(td=12), "FixedInterval-v0", tmp_path / "mine", name="mine")
    chronocooked.report(tmp_path / "mine", tmp_path / "r")
    lines = (tmp_path / "r" / "report.csv").read_text().splitlines()
    models = [line.split(",")[0] for line in lines[1:]]
    assert models[0] == "mine"
    assert {"lstm125 (paper-core)", "cnn-mlp (paper-core)"} <= set(models)
    chronocooked.report(tmp_path / "mine", tmp_path / "r2", baselines=False)
    assert len((tmp_path / "r2" / "report.csv").read_text().splitlines()) == 2


def test_the_default_baselines_are_found_from_the_current_folder_or_the_package(tmp_path, monkeypatch):
    from chronocooked import zoo

    monkeypatch.delenv("CHRONOCOOKED_BASELINES", raising=False)
    clone = tmp_path / "clone"
    (clone / "results" / "paper-core" / "jobs").mkdir(parents=True)
    (clone / "deep" / "folder").mkdir(parents=True)
    monkeypatch.chdir(clone / "deep" / "folder")
    assert zoo._find_default_baselines() == clone / "results" / "paper-core"
    # Outside any clone: the package's own ancestors (a virtual environment inside the
    # clone) or nothing, never a folder without jobs.
    monkeypatch.chdir(tmp_path)
    (clone / "results" / "paper-core" / "jobs").rmdir()
    found = zoo._find_default_baselines()
    package = Path(zoo.__file__).resolve()
    assert found is None or (found / "jobs").is_dir() and found.parent.parent in package.parents
    monkeypatch.setenv("CHRONOCOOKED_BASELINES", str(tmp_path))
    assert zoo._find_default_baselines() is None  # the core reads the variable


def readme_example():
    text = (ROOT / "docs" / "your-agent.md").read_text()
    m = re.search(r"<!-- example: my agent -->\s*```python\n(.*?)```", text, re.S)
    assert m, "docs/your-agent.md has the worked example"
    return m.group(1)


def test_the_readme_example_runs_as_written_in_under_a_minute(tmp_path):
    env = dict(os.environ,
               PYTHONPATH=str(ROOT / "examples" / "python"),
               CHRONOCOOKED_BASELINES=str(ROOT / "results" / "paper-core"),
               CHRONOCOOKED_CACHE=str(tmp_path / "cache"))  # outside the repository: the compiled-in zoo
    start = time.time()
    out = subprocess.run([sys.executable, "-c", readme_example()], cwd=tmp_path, env=env,
                         capture_output=True, text=True)
    seconds = time.time() - start
    assert out.returncode == 0, out.stderr
    assert seconds < 60, f"{seconds:.0f} s"
    # Run outside the repository, the agent came from the package's compiled-in zoo.
    assert list((tmp_path / "cache").glob("zoo-*/lstm125/FixedInterval-v0/model.bpk"))
    rows = (tmp_path / "lab-out" / "leaderboard" / "report.csv").read_text().splitlines()
    models = [r.split(",")[0] for r in rows[1:]]
    assert models[:2] == ["my-pacemaker", "zoo-lstm125"]
    assert "lstm125 (paper-core)" in models
    # The printed decoding R² of both populations: numbers in [0, 1], the LSTM's from 125 units.
    r2 = [float(x) for x in re.findall(r"R² \w+: ([0-9.]+)", out.stdout)]
    assert len(r2) == 2 and all(0 <= x <= 1 for x in r2), out.stdout
