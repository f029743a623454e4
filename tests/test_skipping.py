"""Skipping activations that cannot change anything (Engine.eligible), and budgets instead of a fixed
event limit. Why skipping is exact: docs/ALGORITHM.md, "Skipping what cannot change anything"."""

from __future__ import annotations

import json
import random
import subprocess
import sys

import pytest

from apf_viz.algorithms import get_algorithm
from apf_viz.algorithms.apf_opaque_grid.audit import audit_run, random_pattern, random_solvable_start
from apf_viz.algorithms.examples import Stay
from apf_viz.core.algorithm import Decision
from apf_viz.core.budget import MOVES_PER_KD, paper_D, run_budget
from apf_viz.core.engine import Engine
from apf_viz.core.engine_state import Phase
from apf_viz.core.grid import Direction
from apf_viz.core.run import advance
from apf_viz.core.schedulers import make_scheduler, step_rng
from apf_viz.demos import DEMO_PATTERN, DEMO_START

SCHEDULERS = ["async", "stale-first", "round-robin", "ssync", "fsync"]


def run_cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "apf_viz.cli", *args], capture_output=True, text=True)


def small_case(k: int, seed: int):
    rng = random.Random(k * 7919 + seed)
    start, pattern = random_solvable_start(k, rng), random_pattern(k, rng)
    return start, pattern, [rng.random() < 0.5 for _ in range(k)]


def activation_changes_something(engine: Engine, r: int) -> bool:
    """Replay the run so far into a fresh engine that keeps every activation, then run robot r's whole
    cycle there: does any position or light change?"""
    twin = Engine(
        engine.start, engine.pattern, engine.algorithm, y_up=engine.y_up, skip_noops=False, max_events=None
    )
    for i in range(engine.step_index):
        twin.apply(engine.history.steps.record(i))
    before = (twin.current_points(), list(twin.state.lights))
    for _ in range(3):  # Look, Compute, Move
        twin.step([r])
    return (twin.current_points(), list(twin.state.lights)) != before


@pytest.mark.parametrize("scheduler", ["async", "stale-first", "fsync"])
def test_every_robot_passed_over_would_have_changed_nothing(scheduler):
    start, pattern, y_up = small_case(6, 1)
    e = Engine(start, pattern, get_algorithm("apf-opaque-grid"), y_up=y_up)
    sched = make_scheduler(scheduler)
    rng = random.Random(5)
    checked = 0
    while not e.finished:
        advance(e, sched, 2, steps=rng.randrange(1, 40))
        if e.finished:
            break
        eligible = e.eligible()
        for r in range(e.k):
            if not eligible[r]:
                assert e.state.phase[r] == Phase.IDLE
                assert not activation_changes_something(e, r), (scheduler, e.step_index, r)
                checked += 1
    assert e.outcome == "formed" and checked > 0


def test_eligibility_kept_up_to_date_equals_eligibility_computed_afresh():
    """The engine re-decides only robots whose view changed; a robot whose view changes is eligible again
    at once. Checked against a fresh engine seeking to each step (which decides every robot anew)."""
    start, pattern, y_up = small_case(8, 2)
    e = Engine(start, pattern, get_algorithm("apf-opaque-grid"), y_up=y_up)
    sched = make_scheduler("async")
    while not e.finished:
        advance(e, sched, 4, steps=7)
        fresh = Engine(start, pattern, get_algorithm("apf-opaque-grid"), y_up=y_up)
        for i in range(e.step_index):
            fresh.apply(e.history.steps.record(i))
        assert (e.eligible() == fresh.eligible()).all(), e.step_index
    assert e.outcome == "formed"


@pytest.mark.parametrize("scheduler", SCHEDULERS)
def test_runs_with_and_without_skipping_end_the_same_way(scheduler):
    for seed in range(4):
        start, pattern, y_up = small_case(7, seed)
        outcomes = []
        for skip in (True, False):
            e = Engine(start, pattern, get_algorithm("apf-opaque-grid"), y_up=y_up, skip_noops=skip)
            audit = audit_run(e, scheduler, seed)
            assert audit.ok, audit.problems
            outcomes.append(e.outcome)
        assert outcomes == ["formed", "formed"]


@pytest.mark.slow
def test_all_activations_reproduces_the_runs_before_skipping_existed():
    """Measured with the code before skipping (commit fdaddfc): the built-in demo, seed 3."""
    before = {"async": (4883, 144, 1624), "stale-first": (5306, 168, 1762), "ssync": (5879, 168, 1955)}
    for scheduler, counts in before.items():
        out = run_cli(
            "run", "--robots", str(DEMO_START), "--pattern", str(DEMO_PATTERN), "--scheduler", scheduler,
            "--seed", "3", "--json", "--all-activations",
        )  # fmt: skip
        data = json.loads(out.stdout)
        assert (data["events"], data["moves"], data["cycles"]) == counts and data["skipped"] == 0
        skipped = json.loads(
            run_cli(
                "run", "--robots", str(DEMO_START), "--pattern", str(DEMO_PATTERN), "--scheduler",
                scheduler, "--seed", "3", "--json",
            ).stdout
        )  # fmt: skip
        assert skipped["outcome"] == "formed" and skipped["skipped"] > 0
        if scheduler != "stale-first":  # stale-first's cycles mostly change lights: they are not no-ops
            assert skipped["events"] < counts[0] // 5


def test_a_start_no_robot_can_act_on_is_stuck_at_once_without_any_limit():
    e = Engine([(0, 0), (2, 1), (3, 3)], [(0, 0), (1, 0), (2, 0)], Stay())
    assert (e.outcome, e.state.events) == ("stuck", 0)
    out = run_cli(
        "run", "--robots", str(DEMO_START), "--pattern", str(DEMO_PATTERN), "--algorithm", "stay", "--json"
    )  # fmt: skip
    data = json.loads(out.stdout)
    assert out.returncode == 1 and (data["outcome"], data["events"]) == ("stuck", 0)


class Shuttle:
    """A toy that never settles: every robot moves right, then left, then right… (and never collides:
    a robot only ever uses the point to its right, which nobody else can reach if robots are 3 apart)."""

    name = "shuttle"
    lights = ("off", "right")

    def decide(self, view, pattern) -> Decision:
        if view.light == "off":
            return Decision("right", Direction.RIGHT, "go right", "shuttle.right")
        return Decision("off", Direction.LEFT, "come back", "shuttle.left")


def test_a_livelock_ends_on_the_budget_as_limit():
    start, pattern = [(0, 0), (3, 0)], [(0, 0), (0, 1)]
    budget = run_budget(start, pattern)
    assert budget.max_moves == MOVES_PER_KD * 2 * paper_D(start, pattern)
    e = Engine(start, pattern, Shuttle(), max_moves=budget.max_moves, max_events=budget.max_events)
    advance(e, make_scheduler("async"), 1)
    assert e.outcome == "limit" and e.state.moves == budget.max_moves


@pytest.mark.slow
def test_the_issue_recipe_forms_with_default_options():
    """100 random robots in 60×60, a random 100-point pattern in 40×40: formed, exit 0, no limit met."""
    robots = run_cli("random-robots", "--count", "100", "--width", "60", "--height", "60", "--seed", "7")
    pattern = run_cli("random-pattern", "--count", "100", "--width", "40", "--height", "40", "--seed", "7")
    assert robots.returncode == pattern.returncode == 0
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as d:
        (Path(d) / "r.json").write_text(robots.stdout)
        (Path(d) / "p.json").write_text(pattern.stdout)
        out = run_cli("run", "--robots", f"{d}/r.json", "--pattern", f"{d}/p.json", "--json")
    data = json.loads(out.stdout)
    assert out.returncode == 0 and data["outcome"] == "formed"
    assert data["moves"] < data["max_moves"] // 10 and data["events"] < data["max_events"] // 10


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_stale_first_never_runs_a_cycle_the_skipping_passed_over(seed):
    """Stale-first's oldest snapshot is looked for among robots holding a Move: an idle robot passed
    over (its view answers "same light, stay") is never activated, so a move costs about 3 events
    (it once cost 3 per robot in sight: 120 per move at k = 40)."""
    start, pattern, y_up = small_case(20, seed)
    e = Engine(start, pattern, get_algorithm("apf-opaque-grid"), y_up=y_up)
    scheduler = make_scheduler("stale-first")
    from apf_viz.core.schedulers import step_rng

    while not e.finished:
        eligible = e.eligible().copy()
        record = scheduler.choose(e, step_rng(seed, e.step_index))
        for r in record.robots:
            assert e.state.phase[r] != int(Phase.IDLE) or eligible[r], (e.step_index, r)
        e.apply(record)
    assert e.outcome == "formed" and e.state.events <= 4 * e.state.moves + 4 * e.k


class MoveOnce:
    """A toy: a robot still off moves one cell right and shows it has; then it stays."""

    name = "move-once"
    lights = ("off", "moved")

    def decide(self, view, pattern) -> Decision:
        if view.light == "off":
            return Decision("moved", Direction.RIGHT, "move once", "once.right")
        return Decision("moved", None, "moved already", "once.stay")


@pytest.mark.parametrize("scheduler", ["async", "stale-first"])
def test_deciding_the_stale_robots_in_two_parts_changes_no_run(scheduler, monkeypatch):
    """After a step, the run's end is checked deciding as few of the robots whose views changed as it
    takes to find one that can act; the rest are decided when the scheduler next asks (so the UI shows
    the step first). Each run step for step against an engine that decides them all at once; the last
    case (nobody can act: every robot stale at the start, and none eligible) ends before any step."""
    apf = get_algorithm("apf-opaque-grid")
    cases = [(*small_case(30, seed), apf, "formed") for seed in range(3)]
    cases.append((*small_case(30, 0), Stay(), "stuck"))
    column = [(0, 0), (0, 2), (0, 4), (0, 6)]  # each moves right once: the last move leaves the others stale
    cases.append((column, [(0, 0), (0, 2), (0, 4), (1, 6)], [True, False, True, False], MoveOnce(), "stuck"))
    left_for_later = 0
    for seed, (start, pattern, y_up, algorithm, outcome) in enumerate(cases):
        runs, pending = [], []
        for in_parts in (True, False):
            e = Engine(start, pattern, algorithm, y_up=y_up)
            if not in_parts:  # every stale robot decided first: the check then finds nothing stale
                check = e._active_before_deciding

                def at_once(e=e, check=check) -> bool:
                    e.eligible()
                    return check()

                monkeypatch.setattr(e, "_active_before_deciding", at_once)
            sched, events, left = make_scheduler(scheduler), [], []
            while not e.finished and e.step_index < 20_000:
                events.extend(e.apply(sched.choose(e, step_rng(seed, e.step_index))))
                left.append(e.pending_decisions)
            runs.append((events, e.outcome, e.state.moves))
            pending.append(left)
        assert runs[0] == runs[1]
        assert runs[0][1] == outcome
        left_for_later += sum(1 for parts, at_once in zip(*pending, strict=True) if parts > at_once)
    assert left_for_later > 0
