"""Chronocooked Lab from Python.

* ``import chronocooked`` registers every task as ``chronocooked/<Id>`` with gymnasium
  (``gymnasium.make("chronocooked/Bisection-v0", short=4, long=12)``; vector envs through
  ``gymnasium.make_vec(..., vectorization_mode="vector_entry_point")``).
* :func:`evaluate` runs the lab's reference evaluation protocol with any Python policy and
  writes the same evaluation folder as ``chronocooked eval`` (a leaderboard row for
  ``chronocooked report --eval DIR``).
* :func:`load_eval` / :func:`load_activity` read evaluation folders and activity exports;
  :func:`to_nwb` writes a model run as an NWB file (needs ``pynwb``).
* :mod:`chronocooked.zoo` holds the repository's trained agents (``zoo.load("lstm125/
  FixedInterval-v0")`` is a policy for :func:`evaluate`); :func:`report` writes the
  leaderboard of evaluation folders next to the committed baselines.
"""

from . import _core
from ._core import EVENT_FLAGS, PolicyError, __version__, reference_conditions
from .envs import ChronoEnv, ChronoVectorEnv, overrides, register_envs, task_ids
from . import zoo
from .evaluation import evaluate, load_activity, load_eval
from .zoo import report


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
    "ChronoEnv",
    "ChronoVectorEnv",
    "EVENT_FLAGS",
    "PolicyError",
    "__version__",
    "evaluate",
    "load_activity",
    "load_eval",
    "overrides",
    "reference_conditions",
    "register_envs",
    "report",
    "task_ids",
    "tasks",
    "to_nwb",
    "zoo",
]
