"""Merged-light variants (algorithms/merged_lights.py): ``BASE+merge(a=b)`` shows lights a and b as one
colour, read as a; the model stays honest and a bad merge is one line."""

from __future__ import annotations

import json
import random
import subprocess
import sys

import pytest

from apf_viz.algorithms import get_algorithm
from apf_viz.algorithms.apf_opaque_grid.audit import random_pattern, random_solvable_start
from apf_viz.algorithms.merged_lights import MergedLights
from apf_viz.core.engine import Engine
from apf_viz.core.run import advance
from apf_viz.core.schedulers import make_scheduler


def case(seed: int, k: int = 6):
    rng = random.Random(seed)
    return random_solvable_start(k, rng), random_pattern(k, rng), [rng.random() < 0.5 for _ in range(k)]


def run(algorithm, seed: int, scheduler: str = "async") -> Engine:
    start, pattern, y_up = case(seed)
    e = Engine(start, pattern, algorithm, y_up=y_up, max_events=20_000)  # a livelock ends soon
    advance(e, make_scheduler(scheduler), seed)
    return e


def test_a_merged_name_names_the_variant_and_its_lights():
    alg = get_algorithm("apf-opaque-grid+merge(leader1=decider)")
    assert alg.name == "apf-opaque-grid+merge(leader1=decider)"
    assert alg.lights == ("off", "terminal1", "symmetric", "leader1", "call", "leader", "done")  # first place
    assert get_algorithm(alg.name).name == alg.name  # a trace header names it back
    two = get_algorithm("apf-opaque-grid-literal+merge( call = symmetric , leader=done)")
    assert two.name == "apf-opaque-grid-literal+merge(call=symmetric,leader=done)"
    assert "symmetric" not in two.lights and "done" not in two.lights
    some = get_algorithm("apf-opaque-grid@G1,G2+merge(terminal1=off)")
    assert some.name == "apf-opaque-grid@G1,G2+merge(terminal1=off)"
    assert some.lights[0] == "terminal1"  # the start light, merged, is shown as terminal1


@pytest.mark.parametrize(
    ("name", "says"),
    [
        ("apf-opaque-grid+merge(leader1=leader1)", "a light is one colour already"),
        ("apf-opaque-grid+merge(leader1=blue)", "has no light 'blue'"),
        ("apf-opaque-grid+merge(leader1)", "is not a pair light=light"),
        ("apf-opaque-grid+merge(leader1=decider", "at the end"),
        ("apf-opaque-grid+merge()", "is not a pair"),
        ("apf-opaque-grid+merge(a=b)+merge(c=d)", "one +merge"),
        ("apf-opaque-grid+merge(leader1=decider,decider=call)", "one merge only"),
        ("+merge(leader1=decider)", "follows an algorithm's name"),
        ("nonsense+merge(leader1=decider)", "unknown algorithm 'nonsense'"),
        ("apf-opaque-grid+merge(leader1=os.system)", "is not a pair"),
    ],
)
def test_a_meaningless_merge_is_refused_in_one_line(name, says):
    with pytest.raises(ValueError, match=None) as e:
        get_algorithm(name)
    assert says in str(e.value) and "\n" not in str(e.value)


def test_the_command_line_refuses_a_bad_merge_with_exit_2(tmp_path):
    start, pattern, _ = case(1)
    (tmp_path / "r.json").write_text(json.dumps({"robots": start}))
    (tmp_path / "p.json").write_text(json.dumps({"points": pattern}))
    done = subprocess.run(
        [sys.executable, "-m", "apf_viz.cli", "run", "--robots", str(tmp_path / "r.json"), "--pattern",
         str(tmp_path / "p.json"), "--algorithm", "apf-opaque-grid+merge(leader1=leader1)"],
        capture_output=True, text=True,
    )  # fmt: skip
    assert done.returncode == 2
    assert done.stderr.strip().count("\n") == 0 and "a light is one colour already" in done.stderr


@pytest.mark.parametrize("base", ["apf-opaque-grid", "apf-opaque-grid-literal", "apf-opaque-grid@G1,L2"])
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_the_variant_machinery_without_a_merge_is_the_algorithm_event_for_event(base, seed):
    plain = run(get_algorithm(base), seed, "stale-first" if seed % 2 else "async")
    wrapped = run(MergedLights(get_algorithm(base), []), seed, "stale-first" if seed % 2 else "async")
    assert wrapped.history.events() == plain.history.events()
    assert wrapped.outcome == plain.outcome


class Spy:
    """Wraps an algorithm and keeps every view it is asked about."""

    def __init__(self, algorithm) -> None:
        self.algorithm, self.lights, self.name, self.views = algorithm, algorithm.lights, "spy", []

    def decide(self, view, pattern):
        self.views.append(view)
        return self.algorithm.decide(view, pattern)


@pytest.mark.parametrize("merge", ["leader1=decider", "decider=leader1", "leader=done", "terminal1=off"])
def test_no_robot_shows_or_sees_a_merged_away_light(merge):
    base = Spy(get_algorithm("apf-opaque-grid"))
    variant = MergedLights(base, [tuple(merge.split("="))])
    gone = merge.split("=")[1]
    for seed in (1, 2):
        e = run(variant, seed)
        assert gone not in e.state.lights_used
        assert all(ev.light != gone for ev in e.history.events() if ev.phase == "compute")
    assert base.views and all(
        v.light != gone and all(s.light != gone for s in v.robots) for v in base.views
    )  # the algorithm is only ever asked about the merged colours


def test_a_watch_on_a_merged_away_light_watches_the_merged_colour():
    variant = get_algorithm("apf-opaque-grid+merge(leader1=leader)")
    e = run(variant, 1)
    watched = set()
    for r in range(e.k):
        d = variant.decide(e.look(r), e.pattern)
        if d.watch is not None:
            watched |= d.watch.lights
    assert "leader" not in watched


def test_the_legend_names_both_merged_lights():
    legend = get_algorithm("apf-opaque-grid+merge(leader1=decider)").legend()
    assert list(legend) == list(get_algorithm("apf-opaque-grid+merge(leader1=decider)").lights)
    assert "leader1 = decider (merged)" in legend["leader1"].meaning


def test_a_merged_run_writes_a_trace_that_replays(tmp_path):
    start, pattern, y_up = case(2)
    (tmp_path / "r.json").write_text(json.dumps({"robots": start, "y_up": y_up}))
    (tmp_path / "p.json").write_text(json.dumps({"points": pattern}))
    name = "apf-opaque-grid+merge(leader1=decider)"
    cli = [sys.executable, "-m", "apf_viz.cli"]
    ran = subprocess.run(
        [*cli, "run", "--robots", str(tmp_path / "r.json"), "--pattern", str(tmp_path / "p.json"),
         "--algorithm", name, "--trace", str(tmp_path / "t.jsonl")],
        capture_output=True, text=True,
    )  # fmt: skip
    assert ran.returncode in (0, 1), ran.stderr
    header = json.loads((tmp_path / "t.jsonl").read_text().splitlines()[0])
    assert header["algorithm"] == name
    replayed = subprocess.run(
        [*cli, "replay", "--trace", str(tmp_path / "t.jsonl")], capture_output=True, text=True
    )
    assert replayed.returncode in (0, 1) and "differs" not in replayed.stderr, replayed.stderr


def test_a_merge_is_at_work_where_the_base_sets_the_hidden_light_or_hides_the_start_light():
    from apf_viz.algorithms.merged_lights import AtWork
    from apf_viz.core.view import Seen, Snapshot

    base = get_algorithm("apf-opaque-grid")
    pattern = ((0, 0), (1, 0))
    leftmost = Snapshot("off", (Seen(1, 1, "off"),))  # A1.off.terminal: it turns terminal1
    waiting = Snapshot("off", (Seen(-1, 1, "off"),))  # A1.off.wait: it stays off

    def count(a: str, b: str, view: Snapshot) -> int:
        counted = AtWork(MergedLights(base, [(a, b)]))
        counted.decide(view, pattern)
        return counted.count

    assert count("symmetric", "terminal1", leftmost) == 1  # terminal1 set, shown as symmetric
    assert count("symmetric", "terminal1", waiting) == 0  # nothing hidden in a decision to wait
    assert count("call", "off", waiting) == 1  # off is everyone's start light: hidden from the start
    assert count("leader", "done", leftmost) == 0
