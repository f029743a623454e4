"""Watches: an idle robot's "same light, stay" is trusted until an event touches what it depended on.

The promise each watch makes (apf_opaque_grid/watches.py) is checked after every step of many runs
against a decision on the view computed from scratch; runs with and without watches must be the same
run, step for step; and the engine's side (core/watches.py) is checked event by event."""

from __future__ import annotations

import random

import numpy as np
import pytest

from apf_viz.algorithms import get_algorithm
from apf_viz.algorithms.apf_opaque_grid import LIGHTS
from apf_viz.algorithms.apf_opaque_grid.audit import random_pattern, random_solvable_start
from apf_viz.algorithms.apf_opaque_grid.watches import LATER_LIGHTS, PHASE1_LIGHTS
from apf_viz.core.algorithm import Watch
from apf_viz.core.engine import Engine
from apf_viz.core.quiet_steps import QuietSteps, WalkPath
from apf_viz.core.run import advance
from apf_viz.core.schedulers import make_scheduler
from apf_viz.core.view import Snapshot
from apf_viz.core.visibility import Views
from apf_viz.core.watch_geometry import global_box, robots_in
from apf_viz.core.watches import Watches


def case(k: int, seed: int):
    rng = random.Random(k * 104729 + seed)
    start, pattern = random_solvable_start(k, rng), random_pattern(k, rng)
    return start, pattern, [rng.random() < 0.5 for _ in range(k)]


def fresh_view(e: Engine, r: int) -> Snapshot:
    """Robot r's view built from nothing but the current positions and lights."""
    views = Views(e.state.positions.copy(), list(e.state.lights), e.y_up)
    return Snapshot(e.state.lights[r], views.seen(r)[0])


def broken_promises(e: Engine) -> list[tuple[int, str]]:
    """Watched robots whose decision on their present view, computed afresh, is not a no-op."""
    bad = []
    for r in np.flatnonzero(e._watches.active).tolist():
        decision = e.algorithm.decide(fresh_view(e, r), e.pattern)
        if not decision.is_noop(e.state.lights[r]):
            bad.append((r, decision.rule_id))
    return bad


RUNS = [
    # (algorithm, scheduler, light semantics, k, seeds)
    ("apf-opaque-grid", "async", "compute", 9, range(6)),
    ("apf-opaque-grid", "async", "compute", 16, range(2)),
    ("apf-opaque-grid", "stale-first", "compute", 8, range(4)),
    ("apf-opaque-grid", "ssync", "compute", 8, range(3)),
    ("apf-opaque-grid", "fsync", "compute", 8, range(3)),
    ("apf-opaque-grid", "async", "lc-atomic", 8, range(3)),
    ("apf-opaque-grid-literal", "async", "compute", 7, range(4)),
    ("apf-opaque-grid@G1,LA,P3", "stale-first", "compute", 7, range(3)),
]


@pytest.mark.slow
@pytest.mark.parametrize("algorithm,scheduler,semantics,k,seeds", RUNS)
def test_every_watched_robot_would_still_stay(algorithm, scheduler, semantics, k, seeds):
    watched = 0
    for seed in seeds:
        start, pattern, y_up = case(k, seed)
        e = Engine(start, pattern, get_algorithm(algorithm), y_up=y_up, light_semantics=semantics)
        sched = make_scheduler(scheduler)
        while not e.finished and e.state.events < 20_000:
            advance(e, sched, seed, steps=1)
            e.eligible()  # registers the watches of the robots re-decided after this step
            assert not broken_promises(e), (algorithm, scheduler, seed, e.step_index, broken_promises(e))
            watched += int(e._watches.active.sum())
    assert watched > 0  # the promises were put to the test


@pytest.mark.slow
def test_promises_hold_in_a_larger_run_where_views_hold_dozens_of_robots():
    """k = 30, every third step: the line, the crowd, the done robots and the leader all in sight."""
    start, pattern, y_up = case(30, 7)
    e = Engine(start, pattern, get_algorithm("apf-opaque-grid"), y_up=y_up)
    sched, checked = make_scheduler("async"), 0
    while not e.finished:
        advance(e, sched, 7, steps=3)
        e.eligible()
        assert not broken_promises(e), (e.step_index, broken_promises(e))
        checked += int(e._watches.active.sum())
    assert e.outcome == "formed" and checked > 10_000


@pytest.mark.parametrize("scheduler", ["async", "stale-first", "fsync"])
def test_watching_changes_nothing_in_the_run(scheduler):
    """Watches only spare work: the same steps, events and outcome as asking after every view change."""
    for seed in range(2):
        start, pattern, y_up = case(20, seed)
        runs = []
        for use in (True, False):
            e = Engine(start, pattern, get_algorithm("apf-opaque-grid"), y_up=y_up, use_watches=use)
            advance(e, make_scheduler(scheduler), seed)
            runs.append(
                (
                    e.outcome,
                    e.state.events,
                    e.state.moves,
                    [e.history.steps.record(i) for i in range(e.step_index)],
                )
            )
        assert runs[0] == runs[1]
        assert runs[0][0] == "formed"


@pytest.mark.slow
def test_watches_spare_most_decisions():
    start, pattern, y_up = case(40, 0)
    calls = []
    for use in (True, False):
        e = Engine(start, pattern, get_algorithm("apf-opaque-grid"), y_up=y_up, use_watches=use)
        advance(e, make_scheduler("async"), 0)
        calls.append(e.decide_calls)
    assert calls[0] * 5 < calls[1], calls


def test_the_later_lights_are_every_light_but_phase_1s():
    assert set(LIGHTS) == LATER_LIGHTS | PHASE1_LIGHTS and not LATER_LIGHTS & PHASE1_LIGHTS


# ---------------------------------------------------------------------------- the engine's side
def watches_on(points, lights=None, y_up=None):
    P = np.array(points, dtype=np.int64)
    lights = lights or ["off"] * len(points)
    return P, lights, Watches(P, lights, LIGHTS, y_up or [True] * len(points))


def move(P, w, m, to, occupied=None):
    old = tuple(int(v) for v in P[m])
    P[m] = to
    occupied = occupied if occupied is not None else {tuple(p): i for i, p in enumerate(P.tolist())}
    return w.moved([old], [to], [m], occupied)


def test_a_box_is_touched_by_a_move_into_or_out_of_it_and_flips_with_the_robot():
    P, _, w = watches_on([(0, 0), (5, 5), (-3, 2)], y_up=[False, True, True])
    assert w.register(0, Watch(boxes=((-3, 0, 1, None),)))  # local y ≥ 1 is global y ≤ −1
    assert move(P, w, 1, (5, 4)) == []
    assert move(P, w, 2, (-3, 1)) == []  # global y = 1 is outside (flipped)
    assert move(P, w, 2, (-3, 0)) == [] and move(P, w, 2, (-3, -1)) == [0]
    assert not w.active[0]  # asked again: the watch is gone


def test_a_segment_is_touched_on_its_points_only():
    P, _, w = watches_on([(0, 0), (4, 2), (9, 9)])
    assert w.register(0, Watch(segments=((4, 2),)))
    assert move(P, w, 2, (9, 8)) == []
    P[2] = (3, 2)
    assert move(P, w, 2, (2, 1)) == [0]  # onto the segment's middle point
    w.register(0, Watch(segments=((4, 2),)))
    assert move(P, w, 1, (4, 3)) == [0]  # the witness itself leaves


def test_a_watched_light_coming_into_sight_by_a_reveal():
    # 0 watches for "leader"; 2 (leader) is hidden from 0 behind 1 on the x-axis.
    P, lights, w = watches_on([(0, 0), (1, 0), (2, 0), (0, 5)], ["off", "off", "leader", "off"])
    w.bits[2] = 1 << LIGHTS.index("leader")
    assert w.register(0, Watch(lights=frozenset({"leader"})))
    assert w.register(3, Watch(lights=frozenset({"leader"})))
    assert move(P, w, 1, (1, 1)) == [0]  # 0 sees the leader now; 3 saw it all along
    # A point that another robot enters at once reveals nothing.
    P2, _, w2 = watches_on([(0, 0), (1, 0), (2, 0), (3, 0)], ["off", "off", "off", "leader"])
    w2.bits[3] = 1 << LIGHTS.index("leader")
    w2.register(0, Watch(lights=frozenset({"leader"})))
    old = [(1, 0), (2, 0)]
    P2[1], P2[2] = (1, 1), (1, 0)
    assert w2.moved(old, [(1, 1), (1, 0)], [1, 2], {tuple(p): i for i, p in enumerate(P2.tolist())}) == []


def test_a_relit_robot_concerns_only_the_watchers_that_see_it():
    P, lights, w = watches_on([(0, 0), (1, 0), (2, 0), (0, 3)])
    for r in (0, 3):
        w.register(r, Watch(lights=frozenset({"done"})))
    lights[2] = "done"
    assert w.relit(2, "done") == [3]  # 0 does not see 2 (1 is between)
    assert w.relit(1, "call") == []  # nobody watches call


def test_a_long_segment_is_tested_by_direction_and_length():
    from apf_viz.core.watches import SHORT

    far = 2 * SHORT + 2
    P, _, w = watches_on([(0, 0), (far, far), (3, 4)], y_up=[False, True, True])
    assert w.register(0, Watch(segments=((far, -far),)))  # local +y is global −y: to (far, far) globally
    assert move(P, w, 2, (far + 1, far + 1)) == []  # beyond its end
    assert move(P, w, 2, (3, 4)) == []
    assert move(P, w, 2, (3, 3)) == [0]
    P[2] = (5, 9)
    w.register(0, Watch(segments=((far, -far),)))
    assert move(P, w, 1, (far, far + 1)) == [0]  # the far end itself leaves


def test_a_mover_of_a_watched_light_concerns_only_the_watchers_that_see_it_where_it_stops():
    # 0 and 3 watch leader1; 1 (leader1) moves from behind 2 (hidden from 0) to a point 0 sees.
    P, lights, w = watches_on([(0, 0), (3, 0), (2, 0), (3, 5)], ["off", "leader1", "off", "off"])
    w.bits[1] = 1 << LIGHTS.index("leader1")
    w.register(0, Watch(lights=frozenset({"leader1"})))
    w.register(3, Watch(lights=frozenset({"leader1"}), seen_at=((0, -4),)))
    assert move(P, w, 1, (3, 1)) == [0]  # 3 saw it at (3, 1) before: not news
    w.register(0, Watch(lights=frozenset({"leader1"})))
    P[2] = (2, 2)  # between 0 and (4, 4)
    assert move(P, w, 1, (4, 1)) == [0, 3]
    w.register(0, Watch(lights=frozenset({"leader1"})))
    w.register(3, Watch(lights=frozenset({"leader1"})))
    P[3] = (4, 6)
    assert move(P, w, 1, (4, 4)) == [3]  # hidden from 0 behind (2, 2)


def test_an_occupied_box_wakes_its_watcher_only_when_its_last_robot_leaves():
    # 0 (flipped) waits while a robot stands in local rows 1..3 (global −3..−1) or on its row to its left.
    P, _, w = watches_on([(0, 0), (2, -1), (5, -2), (9, 9)], y_up=[False, True, True, True])
    assert w.register(0, Watch(occupied=((None, None, 1, 3), (None, -1, 0, 0))))
    assert move(P, w, 1, (3, -1)) == [] and move(P, w, 2, (5, -3)) == []  # walking about inside
    assert move(P, w, 1, (3, 0)) == []  # 2 is still inside
    assert move(P, w, 3, (-4, 0)) == []  # a robot arrives on 0's row to its left
    assert move(P, w, 2, (5, -4)) == []  # the band is empty, the row to the left is not
    assert move(P, w, 3, (-4, 1)) == [0]  # every box empty: asked again
    assert not w.active[0]
    P2, _, w2 = watches_on([(0, 0), (1, 1)])
    assert w2.register(0, Watch(occupied=((None, None, 1, 1),)))
    assert move(P2, w2, 1, (1, 2)) == [0]  # the unflipped robot's rows are global rows
    assert not w2.register(0, Watch(occupied=((None, None, 1, 1),)))  # empty already: refused


def test_an_any_of_witness_is_followed_while_it_stays_in_sight_inside_within():
    P = np.array([(0, 0), (2, 3), (9, 9), (-5, 1)], dtype=np.int64)
    at = {(int(x), int(y)): i for i, (x, y) in enumerate(P.tolist())}
    w = Watches(P, ["off"] * 4, LIGHTS, [True] * 4, at)
    upper = (None, None, 1, None)

    def step(m, to):
        old = tuple(int(v) for v in P[m])
        del at[old]
        P[m] = to
        at[to] = m
        return w.moved([old], [to], [m], at)

    assert w.register(0, Watch(any_of=((2, 3),), within=upper))
    assert step(1, (3, 3)) == [] and step(1, (3, 4)) == [] and step(1, (-2, 4)) == []  # walks in sight
    assert step(2, (-1, 2)) == [0]  # steps onto the segment to where the witness is now
    step(2, (7, 7))
    assert w.register(0, Watch(any_of=((-2, 4),), within=upper))
    assert step(1, (-2, 2)) == [] and step(2, (-3, 3)) == []  # a robot behind the witness: no matter
    assert step(1, (-2, 1)) == [] and step(1, (-2, 0)) == [0]  # out of ``within``
    assert w.register(0, Watch(any_of=((-5, 1), (-3, 3)), within=upper))
    assert step(3, (-4, 1)) == [] and step(2, (-4, 2)) == []  # (−4, 2) is in sight: gcd 2, (−2, 1) free
    assert step(3, (-4, 0)) == []  # out of ``within``: the other witness still suffices
    assert step(3, (-4, 1)) == []  # no longer followed: coming back changes nothing
    assert step(1, (-2, 1)) == [0]  # hides the last witness, at (−4, 2)


def test_a_followed_witness_that_changes_its_light_no_longer_counts():
    P, lights, w = watches_on([(0, 0), (1, 2), (3, 3)])
    assert w.register(0, Watch(any_of=((1, 2), (3, 3))))
    lights[1] = "done"
    assert w.relit(1, "done") == []  # the other witness still suffices
    assert move(P, w, 1, (1, 3)) == []  # and the relit one is not followed any more
    lights[2] = "done"
    assert w.relit(2, "done") == [0]


@pytest.mark.parametrize("walk", [0, 3, 32])
def test_a_reveal_is_found_the_same_from_each_shown_robot_as_in_one_pass_over_all(walk, monkeypatch):
    import apf_viz.core.watches as watches_module

    monkeypatch.setattr(watches_module, "WALK", walk)  # 0: numpy only; 3: walks cut short
    rng = random.Random(5)
    for _ in range(200):
        k = rng.randint(3, 25)
        points = rng.sample([(x, y) for x in range(7) for y in range(7)], k + 1)
        p, rest = points[0], points[1:]  # p: the point just vacated
        P, lights, w = watches_on(rest, [rng.choice(LIGHTS) for _ in rest])
        for r in range(k):
            w.bits[r] = 1 << LIGHTS.index(lights[r])
            w._mask[r] = rng.getrandbits(len(LIGHTS))
        one_pass = np.zeros(k, dtype=bool)
        w._revealed_through(p, one_pass)
        each = np.zeros(k, dtype=bool)
        for q in np.flatnonzero(w.bits & np.bitwise_or.reduce(w._mask)).tolist():
            w._revealed_from(q, p, {tuple(x): i for i, x in enumerate(P.tolist())}, each)
        assert one_pass.tolist() == each.tolist()


def test_boxes_and_long_segments_are_found_the_same_one_by_one_as_in_one_numpy_pass(monkeypatch):
    import apf_viz.core.watches as watches_module

    rng = random.Random(11)
    far = watches_module.SHORT + 5
    hits = 0
    for _ in range(40):
        k = 30
        points = rng.sample([(x, y) for x in range(-far, far) for y in range(-far, far)], k)
        P, _, w = watches_on(points, y_up=[rng.random() < 0.5 for _ in range(k)])
        for r in range(k):

            def bound():
                return rng.choice([None, rng.randint(-far, far)])

            boxes = tuple((bound(), bound(), bound(), bound()) for _ in range(rng.randint(0, 2)))
            segments = (
                ((rng.choice([-1, 1]) * far, rng.choice([-1, 0, 1]) * far),) if rng.random() < 0.5 else ()
            )
            w.register(r, Watch(boxes=boxes, segments=segments))
        probes = [tuple(rng.randint(-2 * far, 2 * far) for _ in range(2)) for _ in range(3)]
        monkeypatch.setattr(watches_module, "FEW_REGIONS", 0)
        one_pass = w._touching(probes).tolist()
        monkeypatch.setattr(watches_module, "FEW_REGIONS", 10**9)
        assert w._touching(probes).tolist() == one_pass
        hits += sum(one_pass)
    assert 100 < hits < 40 * 30  # both answers occur


def test_occupied_counts_kept_move_by_move_equal_counts_from_scratch():
    rng = random.Random(3)
    k = 25
    points = rng.sample([(x, y) for x in range(12) for y in range(12)], k)
    P, _, w = watches_on(points, y_up=[rng.random() < 0.5 for _ in range(k)])

    def box():
        x0, y0 = rng.randint(-5, 5), rng.randint(-5, 5)
        x1, y1 = x0 + rng.randint(0, 3), y0 + rng.randint(0, 3)
        return (None if rng.random() < 0.2 else x0, x1, y0, None if rng.random() < 0.2 else y1)

    def watch():
        return Watch(occupied=tuple(box() for _ in range(rng.randint(1, 2))))

    def register(r):
        while not w.register(r, watch()):  # refused: every box is empty already
            pass

    watchers = list(range(12))  # robots 12… move, robots 0…11 watch
    for r in watchers:
        register(r)
    woken = 0
    for _ in range(1500):
        m = rng.randrange(12, k)
        dx, dy = rng.choice([(1, 0), (-1, 0), (0, 1), (0, -1)])
        to = (int(P[m, 0]) + dx, int(P[m, 1]) + dy)
        if to in {tuple(p) for p in P.tolist()}:
            continue
        boxes_of = {r: w._occupied[r][0] for r in watchers}
        hit = move(P, w, m, to)
        for r in watchers:
            fresh = [
                sum(1 for j, (x, y) in enumerate(P.tolist()) if j != r and x0 <= x <= x1 and y0 <= y <= y1)
                for x0, x1, y0, y1 in boxes_of[r]
            ]
            if r in hit:
                assert not any(fresh)
                woken += 1
                register(r)
            else:
                assert w._occupied[r][1] == fresh and any(fresh)
    assert woken >= 3


def test_an_occupied_box_counts_the_robots_in_it_whichever_bounds_are_open():
    # Only a box's finite bounds are compared: rows, strips, half-planes and the plane itself.
    rng = random.Random(5)
    points = rng.sample([(x, y) for x in range(-6, 7) for y in range(-6, 7)], 40)
    y_up = [rng.random() < 0.5 for _ in points]
    P, _, w = watches_on(points, y_up=y_up)
    for _ in range(400):
        r = rng.randrange(len(points))
        x0, y0 = rng.randint(-8, 8), rng.randint(-8, 8)
        local = (x0, x0 + rng.randint(0, 4), y0, y0 + rng.randint(0, 4))
        local = tuple(None if rng.random() < 0.3 else v for v in local)
        gx0, gx1, gy0, gy1 = global_box(*points[r], 1 if y_up[r] else -1, local)
        inside = [j for j, (x, y) in enumerate(points) if j != r and gx0 <= x <= gx1 and gy0 <= y <= gy1]
        assert robots_in(P, (gx0, gx1, gy0, gy1), r) == len(inside)


def test_the_watched_lights_are_those_of_some_registered_watch():
    rng = random.Random(6)
    points = [(x, 0) for x in range(12)]
    _, _, w = watches_on(points)
    held: dict[int, frozenset[str]] = {}
    for _ in range(300):
        r = rng.randrange(len(points))
        w.clear(r)
        held.pop(r, None)
        if rng.random() < 0.6:
            lights = frozenset(rng.sample(LIGHTS, rng.randint(0, 3)))
            assert w.register(r, Watch(segments=((1, 0),), lights=lights))
            held[r] = lights
        watched = set().union(*held.values())
        assert w._watched == sum(1 << LIGHTS.index(light) for light in watched)


@pytest.mark.parametrize("scale", [5, 10**11])
def test_the_first_point_between_a_robot_and_its_watchers_is_found_at_once_as_one_by_one(scale):
    """WalkPath.first_between (one numpy pass over the watchers; Python integers when the offsets are too
    large for int64 products) against WalkPath.between and first_in for each watcher."""
    rng = random.Random(scale)
    for _ in range(400):
        start = (rng.randint(-scale, scale), rng.randint(-scale, scale))
        delta = rng.choice([(1, 0), (-1, 0), (0, 1), (0, -1)])
        path = WalkPath(start, delta)

        def near_line(start: tuple[int, int], horizontal: bool) -> tuple[int, int]:
            # Often on the walk's line, or a few cells off it, so that segments cross it at lattice points.
            off = rng.choice([0, 0, rng.randint(-3, 3), rng.randint(-scale, scale)])
            along = rng.randint(-2 * scale, 2 * scale) if scale < 100 else rng.randint(-40, 40)
            return (start[0] + along, start[1] + off) if horizontal else (start[0] + off, start[1] + along)

        q = near_line(start, delta[1] == 0)
        watchers = [near_line(start, delta[1] == 0) for _ in range(rng.randint(1, 6))]
        n = rng.randint(0, 3 * min(scale, 40))
        expected = min(path.first_in(path.between(q, w), n) for w in watchers)
        assert path.first_between(np.array(q), np.array(watchers, dtype=np.int64), n) == expected


def _random_box(rng: random.Random) -> tuple:
    """A box of a robot's frame that contains its origin, some sides unbounded."""

    def side(lo: bool):
        return None if rng.random() < 0.25 else (-rng.randint(0, 4) if lo else rng.randint(0, 4))

    return (side(True), side(False), side(True), side(False))


def _old_quiet_occupied(w: Watches, path: WalkPath, n: int) -> int:
    """The bound as it was before the count test came first (before eea1ada): the reference."""
    quiet = n
    for boxes, counts in w._occupied.values():
        spans = [path.box(box) for box in boxes]
        if any(count - (lo <= 0 <= hi) for count, (lo, hi) in zip(counts, spans, strict=True)):
            continue
        for t in [1] + [hi + 1 for _, hi in spans]:
            if 1 <= t <= quiet and not any(lo <= t <= hi for lo, hi in spans):
                quiet = t - 1
    return quiet


@pytest.mark.parametrize("seed", range(6))
def test_quiet_steps_is_a_bound_no_single_move_of_the_walk_concerns_a_watcher(seed):
    """QuietSteps.quiet_steps against the moves themselves: random robots, random watches (boxes, segments
    to other robots, occupied boxes, a watched light), a walker; moved one lattice step at a time, it
    concerns no watcher within the bound (the walk fast-forward and forced cycles rely on)."""
    rng = random.Random(seed)
    checked = bound_hit = 0
    for _ in range(120):
        k = rng.randint(3, 14)
        points = rng.sample([(x, y) for x in range(-6, 7) for y in range(-6, 7)], k)
        lights = ["leader" if i == 0 and rng.random() < 0.5 else "off" for i in range(k)]
        P, _, w = watches_on(points, lights, [rng.random() < 0.5 for _ in range(k)])
        walker = rng.randrange(1, k)
        for r in range(k):
            if r == walker or rng.random() < 0.3:
                continue
            x, y = points[r]
            s = 1 if w._flip[r] == 1 else -1
            others = [(px - x, s * (py - y)) for px, py in points if (px, py) != (x, y)]
            watch = Watch(
                boxes=tuple(_random_box(rng) for _ in range(rng.randint(0, 1))),
                segments=tuple(rng.sample(others, rng.randint(0, 1))),
                occupied=tuple(_random_box(rng) for _ in range(rng.randint(0, 2))),
                lights=frozenset({"leader"}) if rng.random() < 0.5 else frozenset(),
            )
            w.register(r, watch)  # refused (an empty occupied box) is fine: r is then not watched
        start = points[walker]
        delta = rng.choice([(1, 0), (-1, 0), (0, 1), (0, -1)])
        n = rng.randint(1, 12)
        path = WalkPath(start, delta)
        assert QuietSteps(w)._quiet_occupied(path, n) == _old_quiet_occupied(w, path, n)
        quiet = QuietSteps(w).quiet_steps(walker, start, delta, n)
        robot_at = {p: i for i, p in enumerate(points)}
        here = start
        for t in range(1, quiet + 1):
            to = (here[0] + delta[0], here[1] + delta[1])
            if to in robot_at:
                break  # the walk would collide: the engine checks the next point itself
            del robot_at[here]
            robot_at[to] = walker
            P[walker] = to
            assert w.moved([here], [to], [walker], robot_at) == [], (seed, t, quiet)
            here = to
            checked += 1
        bound_hit += quiet < n
    assert checked > 150 and bound_hit > 20  # walks were taken, and the bound did cut some


@pytest.mark.slow
def test_a_decision_is_the_same_on_a_view_read_as_arrays_and_read_as_tuples():
    """The rules read large views by ranges off the arrays (Snapshot.column_start, iter_between): every
    robot's decision, its watch included, is the one made on the same view as tuples. k = 60, so views
    are built by the compiled kernel where it is installed, through election and formation."""
    start, pattern, y_up = case(60, 3)
    e = Engine(start, pattern, get_algorithm("apf-opaque-grid"), y_up=y_up)
    sched, compared = make_scheduler("async"), 0
    while not e.finished:
        advance(e, sched, 5, steps=40)
        for r in range(e.k):
            view = e.look(r)
            a = e.algorithm.decide(Snapshot(view.light, columns=view.columns), e.pattern)
            b = e.algorithm.decide(Snapshot(view.light, tuple(view.robots)), e.pattern)
            # Decision equality leaves out the watch and the stride: they are compared here.
            assert (a, a.watch, a.stride) == (b, b.watch, b.stride), (e.step_index, r)
            compared += 1
    assert e.outcome == "formed" and compared > 5_000
