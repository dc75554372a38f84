"""Chronocooked Lab from Python.

* ``import chronocooked`` registers every task as ``chronocooked/<Id>`` with gymnasium
  (``gymnasium.make("chronocooked/Bisection-v0", short=4, long=12)``; vector envs through
  ``gymnasium.make_vec(..., vectorization_mode="vector_entry_point")``).
* :func:`evaluate` runs the lab's reference evaluation protocol with any Python policy and
  writes the same evaluation folder as ``chronocooked eval`` (a leaderboard row for
  ``chronocooked report --eval DIR``).
* :func:`record` records a Python policy's activity on probe trials (``chronocooked record
  --probe --summary``) with its NPZ export and neural summary;
* :func:`fingerprint` runs the lab's mechanisms protocol with your agent and names the
  timing mechanism it resembles; :func:`summarize` gives the neural summary of any
  recording;
* :func:`load_eval` / :func:`load_activity` read evaluation folders and activity exports;
  :func:`to_nwb` writes a model run as an NWB file (needs ``pynwb``).
* :mod:`chronocooked.sb3` turns Stable-Baselines3 models into policies (SB3 optional);
* :mod:`chronocooked.zoo` holds the repository's trained agents (``zoo.load("lstm125/
  FixedInterval-v0")`` is a policy for :func:`evaluate`); :func:`report` writes the
  leaderboard of evaluation folders next to the committed baselines;
* :func:`collect`, :func:`analyse` and :func:`mechanisms` are ``paper collect``,
  ``paper analyse`` and ``mechanisms`` on a study's sweep output and compact results.
"""

from . import _core
from ._core import EVENT_FLAGS, PolicyError, __version__, reference_conditions
from .envs import ChronoEnv, ChronoVectorEnv, overrides, register_envs, reset_options, task_ids
from . import sb3, zoo
from .evaluation import check_export, evaluate, load_activity, load_eval, record
from .fingerprint import CONDITIONS, distance, fingerprint, summarize
from .zoo import report


def probability_of_improvement(x, y):
    """``P(X > Y)`` for a random run of ``x`` and one of ``y`` (sequences of numbers), ties
    counting one half: rliable's probability of improvement for one task."""
    return _core.probability_of_improvement([float(v) for v in x], [float(v) for v in y])


def collect(sweep_out, out):
    """Writes the compact results of every finished job of a sweep's output folder into
    ``out`` (what ``chronocooked paper collect`` writes: ``out/jobs/<job id>/`` with
    ``job.json``, ``metrics.json``, ``episodes.csv``, ``curve.csv`` and the neural summary),
    safe while the sweep runs; returns ``(written, unfinished)`` job counts. The folder is a
    baseline for :func:`report` (``baselines=out``). ``OSError`` naming the folder on a
    missing sweep output or a folder another process writes."""
    import os

    return _core.collect(os.fspath(sweep_out), os.fspath(out))


def analyse(results):
    """``chronocooked paper analyse``: the paper's analyses (and the lab's) of a study's
    compact results ``results`` (from :func:`collect`), written into that folder
    (``tables.md``, ``comparison.csv``, ``agreement.json``, ``figures/``, ``report.html``).
    Returns the study as a dict (``jobs``, ``fi``, ``bisection``, ``comparison``,
    ``agreement``, …) with ``report`` and ``figures`` (paths). ``OSError`` naming the file
    on unreadable results or a folder another process writes."""
    import os

    return _core.analyse(os.fspath(results))


def mechanisms(results, out=None, *, resamples=1000, seed=0):
    """``chronocooked mechanisms``: every model's timing signature in a study's compact
    results ``results`` (e.g. ``results/mechanisms-reference``), the leave-one-seed-out
    identification of the timing mechanisms and each agent's nearest mechanism, written into
    ``out`` (default ``results``: ``signatures.csv``, ``mechanisms.csv``, ``mechanisms.md``,
    ``pairwise.csv``, the fingerprint figures). Returns a dict: ``files``, ``signatures``
    (count), ``agents`` (count), ``held_out`` (per mechanism seed: ``mechanism``, ``seed``,
    ``named``, ``self_distance``, ``other_distance``) and ``verdicts`` (per agent:
    ``agent``, ``nearest``, ``distance``, ``identified``) of the unit view, and ``views``:
    ``held_out`` and ``verdicts`` of the ``units`` and the ``dynamics`` view (basis-free).
    ``ValueError`` when the folder holds no
    finished job; ``OSError`` naming the file otherwise."""
    import os

    return _core.mechanisms(os.fspath(results), None if out is None else os.fspath(out),
                            int(resamples), int(seed))


def export(out, *, activity=None, eval=None, window=200):
    """``chronocooked export``: writes the folder ``out`` from ``activity`` (an
    ``activity.json`` from :func:`record` / :func:`evaluate`, or a folder holding one) and/or
    ``eval`` (an evaluation folder): ``activity.npz`` (+ ``.meta.json``, ``trials.csv``,
    ``units.csv``; aligned arrays up to ``window`` steps after oven-on) and ``episodes.npz``
    (+ metadata and CSV), then the completeness marker ``export.json`` last. Returns the
    files written. ``ValueError`` for inputs that are not what they should be (naming the
    file), ``OSError`` for unreadable inputs or an unwritable / busy ``out``; a bad input
    leaves an earlier export in ``out`` as it was."""
    import os

    return _core.export(os.fspath(out), None if activity is None else os.fspath(activity),
                        None if eval is None else os.fspath(eval), int(window))


def iqm(values, strata=None, level=0.95, resamples=2000, seed=0):
    """The interquartile mean of ``values`` and its stratified percentile bootstrap interval:
    ``(iqm, (lo, hi))`` (``None`` for fewer than 2 values); ``strata`` labels each value's
    stratum (e.g. its task setting), resampled within."""
    return _core.iqm([float(v) for v in values],
                     None if strata is None else [str(s) for s in strata],
                     float(level), int(resamples), int(seed))


def tasks():
    """Every registered task: dicts with id, family, tags, summary, description, source and
    params (key, aliases, allowed values, doc)."""
    return _core.tasks()


def to_nwb(activity, eval_dir, path, **kwargs):
    """Writes one model run as an NWB file (see :func:`chronocooked.nwb.to_nwb`)."""
    from .nwb import to_nwb as _to_nwb

    return _to_nwb(activity, eval_dir, path, **kwargs)


register_envs()

__all__ = [
    "CONDITIONS",
    "ChronoEnv",
    "ChronoVectorEnv",
    "EVENT_FLAGS",
    "PolicyError",
    "__version__",
    "analyse",
    "check_export",
    "collect",
    "evaluate",
    "export",
    "distance",
    "fingerprint",
    "load_activity",
    "load_eval",
    "mechanisms",
    "overrides",
    "iqm",
    "probability_of_improvement",
    "record",
    "reset_options",
    "reference_conditions",
    "register_envs",
    "sb3",
    "report",
    "summarize",
    "task_ids",
    "tasks",
    "to_nwb",
    "zoo",
]
