"""The adversaries: fair within a bound, reproducible from the seed, shaped as their names say."""

from __future__ import annotations

import pytest

from apf_viz.algorithms.examples import CompactLeft
from apf_viz.core.engine import Engine
from apf_viz.core.run import advance
from apf_viz.core.schedulers import AUTOMATIC, ManualScheduler, make_scheduler, starve_bound, step_rng

START = [(x, (x * 7) % 5) for x in range(0, 24, 2)]
PATTERN = [(x, 0) for x in range(len(START))]  # not the start: a start that is the pattern is formed at once
AUTO = list(AUTOMATIC)  # every registered scheduler that chooses by itself


class Forever:
    """Never quiescent: a robot toggles its light every cycle, so a run only ends at the limit."""

    name = "forever"
    lights = ("off", "done")

    def decide(self, view, pattern):
        from apf_viz.core.algorithm import Decision

        return Decision("done" if view.light == "off" else "off", None, "toggle")


@pytest.mark.parametrize("name", AUTO)
def test_every_robot_gets_an_event_within_the_bound(name):
    e = Engine(START, PATTERN, Forever(), max_events=100_000)
    bound = starve_bound(e)
    last = [0] * e.k
    sched = make_scheduler(name)
    for _ in range(2_000):
        record = sched.choose(e, step_rng(9, e.step_index))
        e.step(record.robots, round=record.round)
        for r in record.robots:
            last[r] = e.step_index
        assert max(e.step_index - t for t in last) <= bound + 1


@pytest.mark.parametrize("name", AUTO)
def test_same_seed_same_run_other_seed_other_run(name):
    def run(seed):
        e = Engine(START, PATTERN, CompactLeft(), max_events=20_000)
        advance(e, make_scheduler(name), seed)
        return [(s.record.robots, s.record.round) for s in e.history.steps]

    assert run(3) == run(3)
    if name not in ("fsync", "round-robin"):  # the deterministic ones ignore the seed
        assert run(3) != run(4)


def test_fsync_rounds_are_all_look_then_all_compute_then_all_move():
    e = Engine(START, PATTERN, CompactLeft(), max_events=20_000, skip_noops=False)
    advance(e, make_scheduler("fsync"), 1, steps=9)
    for i, s in enumerate(e.history.steps):
        assert s.record.robots == tuple(range(e.k))
        assert s.record.round == i // 3 + 1
        assert {ev.phase for ev in s.events} == {("look", "compute", "move")[i % 3]}


def test_ssync_rounds_are_atomic_cycles_of_a_subset():
    e = Engine(START, PATTERN, CompactLeft(), max_events=20_000)
    advance(e, make_scheduler("ssync"), 2, steps=30)
    subsets = set()
    for i in range(0, 30, 3):
        look, compute, move = e.history.steps[i : i + 3]
        assert look.record.robots == compute.record.robots == move.record.robots
        assert look.record.round == compute.record.round == move.record.round
        subsets.add(look.record.robots)
    assert len(subsets) > 1 and all(subsets)


def test_round_robin_runs_whole_cycles_in_index_order():
    e = Engine(START, PATTERN, Forever(), max_events=20_000)
    advance(e, make_scheduler("round-robin"), 1, steps=3 * e.k)
    order = [s.record.robots[0] for s in e.history.steps]
    assert order == [r for r in range(e.k) for _ in range(3)]


def test_stale_first_moves_the_oldest_snapshot_after_everyone_has_looked():
    e = Engine(START, PATTERN, CompactLeft(), max_events=20_000)
    sched = make_scheduler("stale-first")
    advance(e, sched, 1, steps=2 * e.k)
    assert all(e.next_event(r) == "move" for r in range(e.k))  # everyone looked and computed first
    record = sched.choose(e, step_rng(1, e.step_index))
    assert record.robots == (int(e.state.look_step.argmin()),)


def test_manual_scheduler_runs_the_picked_robot():
    e = Engine(START, PATTERN, Forever())
    manual = ManualScheduler()
    manual.pick(5)
    manual.pick(5)
    for _ in range(2):
        record = manual.choose(e, step_rng(0, 0))
        e.step(record.robots)
    assert e.next_event(5) == "move" and all(e.next_event(r) == "look" for r in range(e.k) if r != 5)
    with pytest.raises(LookupError):
        manual.choose(e, step_rng(0, 0))


def test_unknown_scheduler_name():
    with pytest.raises(ValueError, match="unknown scheduler"):
        make_scheduler("chaos")
