"""The zoo of trained agents and the leaderboard with committed baselines.

* :func:`agents` lists the zoo's trained agents (``zoo:<model>/<task>``) with their
  provenance (training command, seed, commit, the success they reached);
* :func:`load` returns one as a policy for :func:`chronocooked.evaluate` or a gymnasium
  loop: ``policy(obs, state, episode_start) -> (action, state, activity)`` with reference
  code observations (``uint8 [R, C, 6]``) and its latent population as ``activity``
  (``float32 [units]``);
* :func:`report` writes the leaderboard of evaluation folders next to the committed
  baselines (``results/paper-core`` of the repository by default).

The zoo is found as by the CLI: ``$CHRONOCOOKED_ZOO``; a ``zoo/`` folder (with
``index.json``) in the current folder or an ancestor; else the copy compiled into the
extension, unpacked once into ``$CHRONOCOOKED_CACHE`` (default ``~/.cache/chronocooked``)
— so an installed wheel has the agents without the repository.
"""

import json
import os
from pathlib import Path

from . import _core


def agents():
    """Every zoo agent: a list of dicts with ``name`` (``zoo:<model>/<task>``), ``dir``,
    ``bytes`` and ``provenance`` (model, task, env, seed, preset, env_steps, sweep, job,
    command, commit, train_wall_s, evaluation, study_job, reproduces_study_job)."""
    return json.loads(_core.zoo_agents())["agents"]


def load(name):
    """Zoo agent ``name`` (``"lstm125/FixedInterval-v0"`` or ``"zoo:lstm125/FixedInterval-v0"``)
    as a policy; its files are checked against their SHA-256 records (``ValueError`` naming
    a corrupt file)."""
    return _core.ZooPolicy(str(name))


def provenance(policy):
    """The provenance record (dict) of a policy from :func:`load`."""
    return json.loads(policy.provenance_json)


def report(evals, out, baselines=True, improvement=None):
    """Writes the leaderboard (``report.html``, ``report.md``, ``report.csv``) of the
    evaluation folders ``evals`` (a path or a list of paths, from :func:`chronocooked.evaluate`
    or ``chronocooked eval``) into ``out``, with committed baselines: ``True`` (default) the
    repository's ``results/paper-core`` (``$CHRONOCOOKED_BASELINES``, else found from the
    current folder upwards or from the installed package's folder upwards, as for a
    virtual environment inside the clone), a path or list of compact study results folders, or
    ``False``/``None`` for none. Baseline rows are labelled ``model (study)``. Multi-run
    cells show mean ± SD and the interquartile mean with its stratified bootstrap 95%
    interval (CSV columns ``<metric>_iqm``, ``_iqm_lo``, ``_iqm_hi``). ``improvement``: a
    column (e.g. ``"fi_success"``) whose probability of improvement between every two rows
    is also written (``improvement.csv`` / ``.md``). Returns the written paths."""
    if isinstance(evals, (str, os.PathLike)):
        evals = [evals]
    if baselines is True:
        found = _find_default_baselines()
        extra, default = ([str(found)], False) if found else ([], True)
    elif not baselines:
        extra, default = [], False
    elif isinstance(baselines, (str, os.PathLike)):
        extra, default = [str(baselines)], False
    else:
        extra, default = [str(b) for b in baselines], False
    files = _core.report([str(e) for e in evals], str(out), extra, default, improvement)
    return [Path(f) for f in files]


def _find_default_baselines():
    """``results/paper-core`` of the clone this package runs from: ``None`` when
    ``$CHRONOCOOKED_BASELINES`` is set (the core reads it) or no ancestor of the current
    folder or of this file holds one (the core then says where it looked)."""
    if os.environ.get("CHRONOCOOKED_BASELINES"):
        return None
    for start in (Path.cwd(), Path(__file__).resolve().parent):
        for folder in (start, *start.parents):
            candidate = folder / "results" / "paper-core"
            if (candidate / "jobs").is_dir():
                return candidate
    return None
