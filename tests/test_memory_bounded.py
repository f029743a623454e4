"""Memory bounded by what the robots see, at any coordinate the CLI accepts: no list grows with a distance,
and a run holds at most ``max_recorded`` steps (``scripts/memory_campaign.py`` runs the thousands)."""

from __future__ import annotations

import random
from math import gcd
from pathlib import Path

import pytest

import apf_viz.core.watches as watches
from apf_viz.algorithms import DEFAULT_ALGORITHM, algorithm_from_command_line
from apf_viz.core.engine import Engine
from apf_viz.core.formats import load_pattern, load_robots
from apf_viz.core.grid import as_point
from apf_viz.core.random_configs import random_pattern
from apf_viz.core.run import advance
from apf_viz.core.schedulers import make_scheduler
from apf_viz.core.watch_geometry import MAX_LISTED, lattice_points

DEMOS = Path(__file__).resolve().parent.parent / "demo_patterns"


def wide_start(gen: int, k: int = 12, far: int = 4 * 10**9) -> tuple[list, list]:
    """k robots anywhere in [−far, far]² (the issue's family: 12 robots at about ±4·10⁹)."""
    rng = random.Random(gen)
    robots = sorted({(rng.randint(-far, far), rng.randint(-far, far)) for _ in range(k)})
    return robots, random_pattern(len(robots), 4, 4, gen)


@pytest.mark.parametrize("gen", [1, 4, 8])
def test_a_witness_that_walks_far_is_never_listed_point_by_point(monkeypatch, gen):
    """Before, a watch followed a witness by listing every lattice point between the two robots, however
    far (8,278 points after 3,797 steps of start 1, thousands more as it walked on: 9.6 GB in 30 s)."""
    listed = []

    def spy(x: int, y: int, dx: int, dy: int) -> list:
        listed.append(gcd(dx, dy))
        return lattice_points(x, y, dx, dy)

    monkeypatch.setattr(watches, "lattice_points", spy)
    robots, pattern = wide_start(gen)
    algorithm, _ = algorithm_from_command_line(DEFAULT_ALGORITHM)
    engine = Engine(robots, pattern, algorithm)
    advance(engine, make_scheduler("stale-first"), 1766, steps=6000)
    assert listed and max(listed) <= watches.SHORT


def test_a_segment_too_long_to_list_is_refused():
    with pytest.raises(ValueError, match="is not listed"):
        lattice_points(0, 0, 0, MAX_LISTED + 1)
    assert len(lattice_points(0, 0, 3, 6)) == 3


def test_a_run_holds_at_most_max_recorded_steps_and_says_so():
    robots, pattern = wide_start(2)
    algorithm, _ = algorithm_from_command_line(DEFAULT_ALGORITHM)
    engine = Engine(robots, pattern, algorithm, max_recorded=3000)
    advance(engine, make_scheduler("stale-first"), 1766)
    assert engine.outcome == "limit" and 2999 <= engine.history.entries <= 3000


def test_steps_that_repeat_are_held_once():
    """A Look or a Compute that repeats, cycle after cycle, is one object however often it is recorded."""
    robots, pattern = wide_start(2)
    algorithm, _ = algorithm_from_command_line(DEFAULT_ALGORITHM)
    engine = Engine(robots, pattern, algorithm)
    advance(engine, make_scheduler("stale-first"), 1766, steps=3000)
    entries = [engine.history.packed(i) for i in range(engine.history.length)]
    distinct = {id(e) for e in entries if e[2][-1][1] != "move"}
    repeated = [e for e in entries if e[2][-1][1] != "move"]
    assert len(distinct) < len(repeated) / 4
    assert engine.history.steps[:] == [  # the same steps as recorded, unshared
        s for s in engine.history.steps
    ]


@pytest.mark.parametrize("scheduler", ["fsync", "ssync", "async", "round-robin", "stale-first"])
@pytest.mark.parametrize("semantics", ["compute", "lc-atomic"])
def test_max_events_is_never_passed(scheduler, semantics):
    """Before, a synchronous round of several robots passed it (fsync: 1 → 2, 50 → 53), and so did a Look
    and its Compute as one under lc-atomic (1 → 2)."""
    robots = [as_point(p) for p in load_robots(DEMOS / "starts" / "sym-call-7.json").robots]
    pattern = [as_point(p) for p in load_pattern(DEMOS / "cup-7.json").points]
    algorithm, _ = algorithm_from_command_line(DEFAULT_ALGORITHM)
    for cap in (1, 2, 3, 8, 50):
        engine = Engine(robots, pattern, algorithm, light_semantics=semantics, max_events=cap)
        advance(engine, make_scheduler(scheduler), 1)
        assert engine.outcome == "limit" and engine.state.events <= cap, (cap, engine.state.events)


@pytest.mark.slow
def test_a_walk_down_a_column_another_robot_shares_ends():
    """The family fast-forward does not cover (docs/CLI.md): the far robot walks down the column of a
    robot on the line, whose watch has the walker as its witness, 12,960 cells away; every cycle is a step,
    and the run still forms, well inside the memory cap."""
    from apf_viz.core.adversarial_starts import generate

    case = generate("on-column", 19, k=3, far=20000)
    assert case.robots[2] == (1, 12960) and case.robots[0][0] == 1  # two robots on column x = 1
    algorithm, _ = algorithm_from_command_line(DEFAULT_ALGORITHM)
    engine = Engine(case.robots, case.pattern, algorithm, y_up=case.y_up, fast_forward=True)
    advance(engine, make_scheduler("stale-first"), 19)
    assert engine.outcome == "formed"
    assert engine.history.entries > 12_000  # step by step, not one walk: the docs' claim, held
