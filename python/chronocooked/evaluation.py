"""The lab's evaluation protocol for Python policies, and readers of its outputs."""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np

from . import _core
from .envs import overrides


def evaluate(policy, task: str, out, *, obs_mode: str = "codes", stochastic: int | None = None,
             seed: int = 0, name: str = "python-policy", **params) -> dict:
    """Runs the lab's evaluation protocol of ``task`` with a Python ``policy`` and writes the
    evaluation folder ``out`` exactly as ``chronocooked eval`` does.

    ``policy(obs, state, episode_start) -> (action, state)`` or
    ``-> (action, state, activity)``: ``obs`` in ``obs_mode`` (``"codes"`` ``uint8 [R, C, 6]``
    or ``"onehot"`` ``float32 [channels, R, C]``), ``state`` whatever the policy returned on
    the previous step (``None`` at an episode start), ``episode_start`` True on the first step
    of every episode. ``activity`` (a 1-D float vector, same length every step) is recorded
    as the model's neural activity: ``out/activity.json`` and the NPZ export
    ``out/activity/``.

    Conditions and episodes are those of ``chronocooked eval``: the reference protocol (one
    greedy episode per free start cell per condition) or ``stochastic=N`` episodes per
    condition from random start cells. ``params`` are the task parameters the policy was
    trained with (``--set`` names). Returns a summary dict (episodes, success_rate, paths).

    The folder is a leaderboard row: ``chronocooked report --eval OUT``.
    """
    # The folder is created once the protocol has run: a failing policy leaves nothing.
    out = Path(out)
    return _core.evaluate(policy, task, os.fspath(out), overrides(params), obs_mode,
                          stochastic, int(seed), name)


def record(policy, task: str, out, *, probe: bool = True, tds=None, repeats: int = 1,
           seed: int = 0, obs_mode: str = "codes", name: str = "python-policy",
           summary: bool = True, units_correspond: bool = True, **params) -> dict:
    """Records a Python ``policy``'s neural activity as ``chronocooked record`` records a
    trained run's, and writes it into the folder ``out``.

    ``policy`` as for :func:`evaluate`, returning activity (a 1-D float vector or a dict of
    named vectors, one per population). With ``probe`` (the default, for fixed- and
    peak-interval tasks) it plays peak-interval probe trials: the soup is never released,
    so every trial lasts at least 2 × TD steps after oven-on, the window the neural summary
    analyses. ``tds`` (steps) are the target durations to play (default: the task's TD with
    ``probe``, else the task's evaluation TDs); each is played from every free start cell,
    ``repeats`` times (1–100, repetition ``r`` seeded ``seed + r``).

    Writes ``activity.json``, the NPZ export ``activity/`` (:func:`load_activity` reads it)
    and, with ``summary``, ``activity.summary.json`` (units' categories, speed,
    sequentiality, decoding error; with two TDs the scaling factor — per unit only when
    ``units_correspond``, i.e. one network timed both). Nothing is written when the policy
    fails (:class:`chronocooked.PolicyError` with episode and step) or returns no activity
    (``ValueError``).

    Returns a dict: ``out``, ``task`` and ``env`` (what was played), ``tds``, ``trials``,
    ``units``, ``files`` and ``summary`` (the per-population summaries).
    """
    if tds is not None:
        tds = [int(t) for t in tds]
    return _core.record(policy, task, os.fspath(Path(out)), overrides(params), bool(probe),
                        tds, int(repeats), int(seed), obs_mode, name, bool(summary),
                        bool(units_correspond))


def read_records(path) -> list[dict]:
    """The per-episode records (``records.jsonl``) of an evaluation folder as dicts with
    ``condition`` and ``episode``; errors name the file and line."""
    path = Path(path)
    records = path / "records.jsonl"
    if not records.is_file():
        raise FileNotFoundError(f"{records}: no records.jsonl ({path} is not an eval folder)")
    out = []
    with open(records) as f:
        for line_no, line in enumerate(f, 1):
            if not line.strip():
                continue
            try:
                r = json.loads(line)
            except json.JSONDecodeError as err:
                raise ValueError(f"{records}:{line_no}: not an evaluation record ({err})") from None
            if not (isinstance(r, dict) and "condition" in r and "episode" in r):
                raise ValueError(
                    f"{records}:{line_no}: not an evaluation record (needs condition and episode)")
            out.append(r)
    return out


def _first(infos, event):
    for info in infos:
        if event in info["events"]:
            return info
    return None


def load_eval(path):
    """Reads an evaluation folder (``chronocooked eval`` or :func:`evaluate`).

    Returns ``(episodes, conditions)``, two pandas DataFrames: one row per episode
    (condition kind/task/TD/factor/never_ready, start cell, seed, reward, success, steps,
    ``first_check`` = oven timer at the first oven check (−1 if none), ``oven_off_time``,
    ``counter``) and one row per condition of ``metrics.json`` (its summary fields).
    ``ImportError`` naming the extra to install when pandas is missing.
    """
    try:
        import pandas as pd
    except ImportError as e:
        raise ImportError(
            "load_eval returns pandas DataFrames: install pandas "
            "(pip install 'chronocooked[analysis]', or './python[analysis]' from the clone)"
        ) from e

    path = Path(path)
    rows = []
    for r in read_records(path):
        c, e = r["condition"], r["episode"]
        infos = e["infos"]
        check = _first(infos, "oven_check")
        last = infos[-1] if infos else {}
        rows.append({
            "kind": c["kind"], "task": c["task"], "td": c["td"],
            "factor": c.get("factor"), "never_ready": c.get("never_ready"),
            "start_row": e["start"][0], "start_col": e["start"][1], "seed": e["seed"],
            "reward": e["reward"], "success": e["success"], "steps": len(e["actions"]),
            "first_check": check["timer_at_action"] if check else -1,
            "oven_off_time": last.get("oven_off_time", -1),
            "counter": last.get("counter"),
        })
    episodes = pd.DataFrame(rows)
    metrics_path = path / "metrics.json"
    conditions = pd.DataFrame()
    if metrics_path.is_file():
        metrics = json.loads(metrics_path.read_text())
        flat = []
        for c in metrics.get("conditions", []):
            row = {}
            for k, v in c.items():
                if isinstance(v, dict):
                    row.update({f"{k}.{kk}": vv for kk, vv in v.items()})
                else:
                    row[k] = v
            flat.append(row)
        conditions = pd.DataFrame(flat)
    return episodes, conditions


def _npz_path(path) -> Path:
    path = Path(path)
    if path.is_dir():
        for cand in (path / "activity.npz", path / "activity" / "activity.npz"):
            if cand.is_file():
                return cand
        raise FileNotFoundError(f"{path}: no activity.npz (export one with `chronocooked export --activity`)")
    if not path.is_file():
        raise FileNotFoundError(f"{path}: no such activity export")
    return path


def check_export(folder) -> None:
    """Checks that ``folder`` holds a complete export: its marker ``export.json`` (written
    last by ``chronocooked export`` and :func:`evaluate`) exists and every file it lists has
    the recorded size and SHA-256. ``FileNotFoundError`` when the marker is missing (an
    interrupted export, or one from an older version: rerun it); ``ValueError`` naming the
    file when one differs (the folder mixes two exports)."""
    import hashlib

    folder = Path(folder)
    marker = folder / "export.json"
    if not marker.is_file():
        raise FileNotFoundError(
            f"{marker}: missing — the export in {folder} is incomplete (interrupted, or written "
            "by an older version): rerun `chronocooked export`")
    try:
        files = json.loads(marker.read_text())["files"]
    except (ValueError, KeyError, TypeError) as e:
        raise ValueError(f"{marker}: not an export marker ({e})") from None
    for f in files:
        p = folder / f["name"]
        data = p.read_bytes()
        if len(data) != f["bytes"] or hashlib.sha256(data).hexdigest() != f["sha256"]:
            raise ValueError(f"{p}: differs from its record in {marker} (the folder mixes two "
                             "exports): rerun `chronocooked export`")


def load_activity(path):
    """Reads an activity export (``activity.npz`` + ``activity.meta.json``, from
    ``chronocooked export`` or :func:`evaluate`; a folder holding them also works). An
    incomplete or mixed export is refused (:func:`check_export`).

    Returns ``(arrays, meta)``: a dict of numpy arrays (``activity`` ``[T_total, N]``,
    ``trial_offsets`` ``[K+1]``, ``aligned`` ``[K', W, N]``, ``td``, ``start``, event arrays,
    …) and the metadata dict (model, task, seed, dt, units, array descriptions).
    """
    npz = _npz_path(path)
    # Only a complete export is read: the marker, then every file as recorded.
    check_export(npz.parent)
    with np.load(npz, allow_pickle=False) as data:
        arrays = {k: data[k] for k in data.files}
    meta_path = npz.with_name(npz.name[: -len(".npz")] + ".meta.json")
    meta = json.loads(meta_path.read_text())
    return arrays, meta
