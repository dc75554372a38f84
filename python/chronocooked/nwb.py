"""NWB export of one recorded model run (needs ``pynwb``).

Time base: the env step. Every array uses ``t = step · dt`` seconds with the dataset's
``dt`` (1 by convention: one env step = one second of model time); trials are concatenated
in the order the protocol played them.

Written file:

* ``processing/model/unit_activity`` — ``TimeSeries [time, units]`` with ``rate = 1/dt``
  (the model's activity behind each action);
* ``trials`` — one row per episode: ``td``, ``start_row``, ``start_col``, ``reward``,
  ``success``, ``condition`` (protocol condition kind), start/stop times;
* ``events/task_events`` — an ``EventsTable``: one row per task event (oven_on, oven_ready,
  oven_check, pickup, delivery, reward, sink, button; oven_on2/3 when a multi-oven task's
  second/third oven turns on; ready/set, the reproduction task's cues) with its timestamp, name, trial and
  step;
* ``processing/behavior/Position/agent_position`` — grid cell ``(row, col)`` after each
  step; ``processing/behavior/actions/action`` — action codes (0 wait, 1 down, 2 up,
  3 right, 4 left, 5 interact);
* session metadata: model, task, overrides, seed and the task configuration (JSON) in
  ``session_id`` / ``experiment_description`` / ``notes``.
"""

from __future__ import annotations

import datetime as _dt
import json
import os
import uuid
from pathlib import Path

import numpy as np

from .evaluation import load_activity, read_records


def to_nwb(activity, eval_dir, path, *, overwrite: bool = False, experimenter=None,
           institution: str | None = None, lab: str | None = None) -> Path:
    """Writes the model run recorded in ``activity`` (an ``activity.npz`` export, a folder
    holding one, or the ``(arrays, meta)`` pair of :func:`load_activity`) with the episodes
    of the evaluation folder ``eval_dir`` (same protocol run: :func:`chronocooked.evaluate`
    writes both) to the NWB file ``path`` (written to a temporary file, then renamed).
    ``experimenter`` / ``institution`` / ``lab`` fill the NWB session metadata. Returns
    ``path``.
    """
    try:
        from pynwb import NWBHDF5IO, NWBFile, TimeSeries
        from pynwb.behavior import BehavioralTimeSeries, Position, SpatialSeries
        from pynwb.file import Subject
    except ImportError as e:  # pragma: no cover - depends on the installation
        raise ImportError(
            "the NWB export needs pynwb: pip install 'chronocooked[nwb]' (or pynwb)") from e

    arrays, meta = activity if isinstance(activity, tuple) else load_activity(activity)
    eval_dir = Path(eval_dir)
    path = Path(path)
    if path.exists() and not overwrite:
        raise FileExistsError(f"{path} exists (pass overwrite=True to replace it)")
    records = read_records(eval_dir)
    info = json.loads((eval_dir / "eval.json").read_text())
    act = np.asarray(arrays["activity"], dtype=np.float32)
    offsets = np.asarray(arrays["trial_offsets"], dtype=np.int64)
    k = len(offsets) - 1
    if len(records) != k:
        raise ValueError(
            f"{eval_dir} holds {len(records)} episodes but the activity {k} trials: "
            "they are not from the same run (write both with chronocooked.evaluate)")
    for i, r in enumerate(records):
        steps = len(r["episode"]["actions"])
        if steps != offsets[i + 1] - offsets[i]:
            raise ValueError(
                f"episode {i}: {steps} steps in {eval_dir} but {offsets[i + 1] - offsets[i]} "
                "in the activity: not the same run")
    dt = float(meta.get("dt", 1.0))
    model = meta.get("model", info.get("model", "model"))
    task = meta.get("task", info.get("task", ""))
    seed = int(meta.get("seed", info.get("seed", 0)))
    env = meta.get("env", info.get("env", []))
    started = _dt.datetime.fromtimestamp(
        os.path.getmtime(eval_dir / "eval.json"), tz=_dt.timezone.utc).replace(microsecond=0)
    ident = str(uuid.uuid5(uuid.NAMESPACE_URL,
                           f"chronocooked:{model}:{task}:{seed}:{','.join(env)}:{started.isoformat()}"))
    config = {"model": model, "task": task, "env": env, "seed": seed, "dt": dt,
              "protocol": info.get("mode")}
    nwb = NWBFile(
        session_description=f"Chronocooked Lab: model {model} playing {task} "
                            f"(evaluation protocol, {k} episodes)",
        identifier=ident,
        session_start_time=started,
        session_id=f"{model}-{task}-seed{seed}",
        experiment_description="Simulated agent in the Chronocooked interval-timing tasks; "
                               "configuration: " + json.dumps(config, sort_keys=True),
        notes=json.dumps(config, sort_keys=True),
        keywords=["interval timing", "reinforcement learning", "Chronocooked", model, task],
        source_script="chronocooked.nwb.to_nwb",
        source_script_file_name="chronocooked/nwb.py",
        experimenter=experimenter,
        institution=institution,
        lab=lab,
    )
    # A simulated agent has no species, sex or age: NCBI's "synthetic construct" taxon,
    # sex "O" (other) and age P0D by convention, so that the required subject fields are set.
    nwb.subject = Subject(
        subject_id=f"{model}-seed{seed}",
        description=f"simulated agent: model {model} (Chronocooked Lab), seed {seed}; species, "
                    "sex and age are conventions (no organism)",
        species="http://purl.obolibrary.org/obo/NCBITaxon_32630",
        sex="O",
        age="P0D",
    )
    model_mod = nwb.create_processing_module(
        name="model", description=f"Activity of the units of model {model} (one row per env step)")
    model_mod.add(TimeSeries(
        name="unit_activity", data=act, unit="a.u.", rate=1.0 / dt, starting_time=0.0,
        description=f"Activity of the {act.shape[1]} units of {model} behind each action, "
                    "[time, units]; trials concatenated (see the trials table)",
        comments="units: " + json.dumps(meta.get("units", meta.get("populations", []))),
    ))
    for name, desc in [("td", "target duration of the episode (steps)"),
                       ("start_row", "start cell row"), ("start_col", "start cell column"),
                       ("reward", "total reward of the episode"),
                       ("success", "full-reward delivery"),
                       ("condition", "evaluation condition kind (fi, pi, bisection, …)")]:
        nwb.add_trial_column(name=name, description=desc)
    for i, r in enumerate(records):
        e, c = r["episode"], r["condition"]
        nwb.add_trial(start_time=float(offsets[i] * dt), stop_time=float(offsets[i + 1] * dt),
                      td=int(e["td"]), start_row=int(e["start"][0]), start_col=int(e["start"][1]),
                      reward=float(e["reward"]), success=bool(e["success"]),
                      condition=str(c["kind"]))
    behavior = nwb.create_processing_module(
        name="behavior", description="Agent behaviour and task events in the kitchen grid")
    codes = meta.get("event_codes", {})
    names = {int(c): n for c, n in codes.items()} if isinstance(codes, dict) else {}
    et = np.asarray(arrays.get("event_trial", []), dtype=np.int64)
    es = np.asarray(arrays.get("event_step", []), dtype=np.int64)
    ec = np.asarray(arrays.get("event_code", []), dtype=np.int64)
    events = nwb.create_events_table(
        name="task_events",
        description="Task events (oven_on, oven_ready, oven_check, pickup, delivery, reward, "
                    "sink, button, oven_on2, oven_on3, ready, set); timestamp = start of the env step the "
                    "event happened in",
        source_description="Chronocooked env step information (info.events)",
    )
    # Typed empty columns when no event happened (an agent that never acts on the task):
    # pynwb cannot infer a dtype from an empty list.
    empty = len(et) == 0
    events.add_column(name="event", description="event name",
                      **({"data": np.array([], dtype="U")} if empty else {}))
    events.add_column(name="trial", description="trial (episode) index",
                      **({"data": np.array([], dtype=np.int64)} if empty else {}))
    events.add_column(name="step", description="step of the event within its trial",
                      **({"data": np.array([], dtype=np.int64)} if empty else {}))
    for k, s, c in zip(et.tolist(), es.tolist(), ec.tolist()):
        events.add_row(timestamp=float((offsets[k] + s) * dt), event=names.get(c, f"event_{c}"),
                       trial=int(k), step=int(s))
    pos = np.asarray([i["agent"] for r in records for i in r["episode"]["infos"]], dtype=np.float64)
    actions = np.asarray([a for r in records for a in r["episode"]["actions"]], dtype=np.int64)
    position = Position(name="Position")
    position.add_spatial_series(SpatialSeries(
        name="agent_position", data=pos, reference_frame="kitchen grid, (row, col) of the cell "
        "after the step's action, (0, 0) = top-left cell", unit="n.a.", rate=1.0 / dt,
        starting_time=0.0, description="agent grid cell (row, col) after each step, in cells"))
    behavior.add(position)
    behavior.add(BehavioralTimeSeries(name="actions", time_series=[TimeSeries(
        name="action", data=actions, unit="n.a.", rate=1.0 / dt, starting_time=0.0,
        description="action code per step: 0 wait, 1 down, 2 up, 3 right, 4 left, 5 interact")]))
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.stem + ".tmp.nwb")
    with NWBHDF5IO(os.fspath(tmp), "w") as io:
        io.write(nwb)
    os.replace(tmp, path)
    return path


def main(argv=None) -> int:
    """``python -m chronocooked.nwb ACTIVITY EVAL_DIR OUT.nwb`` (used by
    ``chronocooked export --format nwb``)."""
    import argparse

    ap = argparse.ArgumentParser(prog="python -m chronocooked.nwb", description=main.__doc__)
    ap.add_argument("activity", help="activity.npz export (or a folder holding it)")
    ap.add_argument("eval_dir", help="evaluation folder of the same run")
    ap.add_argument("out", help="NWB file to write")
    ap.add_argument("--overwrite", action="store_true")
    args = ap.parse_args(argv)
    try:
        path = to_nwb(args.activity, args.eval_dir, args.out, overwrite=args.overwrite)
    except (OSError, ValueError, KeyError) as e:
        print(f"error: {e}", file=__import__("sys").stderr)
        return 1
    print(path)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
