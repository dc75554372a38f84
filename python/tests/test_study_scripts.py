"""Known answers for the study scripts under scripts/ that RESULTS quotes."""

import importlib.util
import json

from conftest import ROOT


def load_script(name):
    """Import scripts/<name>.py as a module (its file name has hyphens)."""
    spec = importlib.util.spec_from_file_location(name.replace("-", "_"), ROOT / "scripts" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def bisection_episode(d, start, route, short_side):
    """A bisection record, as `eval` writes it: the agent waits at (3, 0), puts the onion, then
    follows `route` (one cell per step, the last cell repeated) while the oven is on; the oven
    turns ready after d steps and the agent delivers to the counter of the side it stands on
    (`short_side(cell)`)."""
    infos = [{"events": [], "agent": [3, 0], "oven_state": 0, "counter": None}] * 3
    infos = infos + [{"events": ["onion_in"], "agent": [3, 0], "oven_state": 1, "counter": None}]
    for t in range(1, d + 1):
        cell = route[min(t - 1, len(route) - 1)]
        infos.append({"events": [], "agent": list(cell), "oven_state": 1 if t < d else 2, "counter": None})
    choice = "short" if short_side(tuple(infos[-1]["agent"])) else "long"
    infos.append({"events": ["pickup"], "agent": infos[-1]["agent"], "oven_state": 0, "counter": None})
    infos.append({"events": ["delivery"], "agent": infos[-1]["agent"], "oven_state": 0, "counter": choice})
    return {"condition": {"td": d}, "episode": {"start": list(start), "infos": infos}}


def write(path, records):
    path.write_text("".join(json.dumps(r) + "\n" for r in records))


def test_a_route_is_a_clock_and_standing_still_is_not(tmp_path):
    script = load_script("frame-stack-trajectories")
    # A walker: a route of 10 distinct cells; its cell tells the time since the put exactly,
    # and the side it is on when the oven turns ready is its answer.
    route = [(2, 0), (1, 0), (1, 1), (2, 1), (2, 2), (1, 2), (0, 1), (3, 2), (3, 1), (0, 0)]
    walker = [bisection_episode(d, s, route, lambda c: route.index(c) < 4)
              for d in range(1, 11) for s in [(1, 0), (2, 1)]]
    write(tmp_path / "walk.jsonl", walker)
    m = script.job_rows(tmp_path / "walk.jsonl", k=4)
    assert m["t_window"] == 1.0
    assert m["choice_window"] == 1.0 and m["choice_cell"] == 1.0
    # The start cell tells nothing: both starts see every duration, half short, half long.
    assert abs(m["choice_start"] - 0.6) < 1e-12  # 4 of the 10 durations short: the majority is 6 / 10
    # A still agent: one cell at every step, so one window. It tells elapsed times 1 .. 9 of
    # the durations 1 .. 10 only as well as always guessing the most frequent one (t = 1:
    # 9 of the 45 steps while the oven is on).
    still = [bisection_episode(d, (1, 0), [(3, 0)], lambda c: True) for d in range(1, 11)]
    write(tmp_path / "still.jsonl", still)
    m = script.job_rows(tmp_path / "still.jsonl", k=4)
    on_steps = sum(d - 1 for d in range(1, 11))
    assert abs(m["t_window"] - 9 / on_steps) < 1e-12
    assert m["choice_start"] == 1.0


def test_purity_is_the_majority_share():
    script = load_script("frame-stack-trajectories")
    assert script.purity([("a", 1), ("a", 1), ("a", 2), ("b", 3)]) == 0.75
    assert script.purity([]) != script.purity([])  # NaN: nothing to tell
