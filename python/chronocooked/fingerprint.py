"""Which timing mechanism does your agent use? One call: :func:`fingerprint`.

The lab's mechanisms study trains every timing mechanism (drift-diffusion, striatal beat
frequency, three kinds of time cells) on three conditions — fixed interval at TD 6 and at
TD 12, bisection 4–12 — evaluates each with the reference protocol and records it on
peak-interval probe trials. Its behaviour (first-check CV and its trend, peak time and
spread, Weber fraction, bisection point) and its activity (unit categories, temporal
scaling between the two TDs, decoding error) form a *signature*. :func:`fingerprint` runs
the same protocol with your policies and places your agent's signature among the
committed mechanism signatures, in two views side by side:

* the *unit view* reads single-unit categories (ramp, time field, oscillating …): they
  depend on the basis of the units, and change when the units are mixed;
* the *dynamics view* reads the population trajectory's basis-free signature (participation
  ratio, speed trend, turning, straightness, continuation past the interval, the spectrum
  of a linear dynamics fit): the same for any orthogonal mixing of the
  units, so the same verdict for the same dynamics in another basis.

:func:`distance` compares two fingerprinted agents (or seeds) on the mechanisms' scale.
"""

from __future__ import annotations

import os
from pathlib import Path

from . import _core

#: The protocol's conditions: name -> (task, params). A mapping of policies uses these
#: names; a ``make_policy(task, params)`` factory is called with these arguments.
CONDITIONS = {
    "fi-td6": ("FixedInterval-v0", {"td": 6}),
    "fi-td12": ("FixedInterval-v0", {"td": 12}),
    "bisection-4-12": ("Bisection-v0", {"short": 4, "long": 12}),
}


def fingerprint(policies, out, *, seed: int = 0, obs_mode: str = "codes",
                units_correspond: bool = False, name: str = "python-agent",
                draws: int | None = None, resamples: int = 1000) -> dict:
    """Runs the mechanisms protocol with your agent and names the timing mechanism it
    resembles.

    ``policies``: a callable ``make_policy(task, params) -> policy`` (called once per
    condition of :data:`CONDITIONS`, e.g. ``make_policy("FixedInterval-v0", {"td": 6})``)
    or a mapping condition name -> policy. A policy is what :func:`chronocooked.evaluate`
    takes: ``policy(obs, state, episode_start) -> (action, state[, activity])``, activity a
    1-D float vector or a dict of named vectors (populations).

    Each condition is evaluated with the reference protocol, every free start cell played
    ``draws`` times (default: as many as the lab's noisy timing models get, 16), and the
    fixed-interval conditions are also recorded on peak-interval probe trials (soup
    withheld, windows of 2 × TD). ``seed`` seeds every episode of the protocol, the
    category tests and the bootstrap. ``units_correspond``: whether unit ``j`` of your TD-6
    policy is unit ``j`` of your TD-12 policy (one network timing both, or copies of one
    model). Only then is the per-unit scaling factor defined where the population geometry
    cannot tell (a straight ramp); separately trained networks: leave it ``False``.

    Writes into ``out``: one folder per condition (``<condition>/eval/`` as
    ``chronocooked eval`` writes it, ``activity.json`` and ``activity.summary.json`` of the
    probe trials), then ``fingerprint.md``, ``fingerprint.html`` (a card in the style of
    the report's mechanism cards), ``fingerprint.png`` and, last, ``fingerprint.json``.
    Nothing is written when a policy fails (:class:`chronocooked.PolicyError`, with the
    condition, episode and step).

    Returns a dict: ``signature`` (feature -> value), ``missing`` (features the agent
    lacks, e.g. the neural ones without activity), ``distances`` (per mechanism, nearest
    first: ``distance`` in seed-to-seed SDs of a mechanism, ``self_range`` — the distances
    of that mechanism's own held-out seeds —, ``limit`` — the upper 99% prediction limit
    for a new seed's distance — and ``bootstrap_share``), ``nearest``, ``identified`` (the
    distance lies within the nearest mechanism's limit), ``verdict`` (one sentence),
    ``reference_identification`` and ``files`` — these top-level keys are the unit view's;
    ``units`` and ``dynamics`` hold each view's ``distances``, ``nearest``, ``identified``,
    ``verdict``, ``missing`` and ``reference_identification``; ``views_agree`` says whether
    both views give the same verdict and ``agreement`` says so in a sentence.
    """
    kwargs = {"seed": int(seed), "obs_mode": obs_mode, "units_correspond": bool(units_correspond),
              "name": name, "resamples": int(resamples)}
    if draws is not None:
        kwargs["draws"] = int(draws)
    return _core.fingerprint(policies, os.fspath(Path(out)), **kwargs)


def summarize(path, *, units_correspond: bool = False, seed: int = 0) -> list:
    """The neural summary of a recording: ``path`` is an evaluation folder with activity
    (from :func:`chronocooked.evaluate` or ``chronocooked eval --activity``) or an
    ``activity.json``. Writes ``activity.summary.json`` beside it (what ``chronocooked
    record --summary`` writes) and returns one dict per population: unit categories,
    decoding error, scaling between TDs (``units_correspond`` as in :func:`fingerprint`)."""
    return _core.summarize(os.fspath(Path(path)), units_correspond=bool(units_correspond),
                           seed=int(seed))


def distance(a, b, *, view: str = "dynamics") -> float:
    """The distance between two fingerprinted agents (folders written by
    :func:`fingerprint` or ``chronocooked fingerprint``: agent against agent, seed against
    seed) in ``view`` (``"dynamics"`` or ``"units"``), on the scale of the committed
    mechanisms: each feature in units of its seed-to-seed SD within a mechanism, as the
    distances and identification limits of :func:`fingerprint` are. NaN when they share no
    feature of the view."""
    return _core.fingerprint_distance(os.fspath(Path(a)), os.fspath(Path(b)), view=view)
