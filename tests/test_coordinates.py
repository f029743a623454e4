"""Exact geometry over the whole supported range |x|, |y| ≤ COORD_LIMIT, and a clear refusal beyond it.

Two oracles: the lattice walk (every lattice point inside a segment, for configurations of small span
anywhere in the range) and betweenness in Python's unbounded integers (a robot strictly inside the
segment: collinear and between), for robots far apart."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from apf_viz.algorithms import get_algorithm
from apf_viz.algorithms.apf_opaque_grid.audit import audit_run
from apf_viz.core.engine import Engine, EngineError
from apf_viz.core.formats import InputError, parse_pattern, parse_robots, parse_trace
from apf_viz.core.grid import COORD_LIMIT, visible_from
from apf_viz.core.schedulers import make_scheduler, step_rng
from apf_viz.core.view import Seen
from apf_viz.core.visibility import Views
from tests.oracle import visible_by_betweenness, visible_by_lattice_walk

L = COORD_LIMIT


# ------------------------------------------------------------------------------------------ the cases
def test_robots_far_apart_see_each_other_as_the_definition_says():
    points = [(0, 0), (1, 1), (2**33 + 1, 1)]  # today's key mixed up two directions: robot 0 saw one robot
    for i in range(3):
        assert visible_from(np.array(points), i).tolist() == visible_by_betweenness(points, i)
    assert visible_from(np.array(points), 0).tolist() == [1, 2]


def test_a_neighbour_far_below_does_not_hide_the_one_beside():
    points = [(0, 0), (1, -(2**32)), (-1, 0)]
    assert visible_from(np.array(points), 0).tolist() == [1, 2]
    engine = Engine(points, [(0, 0), (1, 0), (2, 0)], get_algorithm("apf-opaque-grid"), y_up=[True] * 3)
    scheduler = make_scheduler("round-robin")
    looks = 0
    for _ in range(3_000):  # today robot 0 walked onto robot 2 here: a collision on a solvable start
        if engine.finished:
            break
        now = engine.current_points()
        for event in engine.apply(scheduler.choose(engine, step_rng(1, engine.step_index))):
            if event.phase == "look":  # every Look sees what the definition says it sees
                assert list(event.sees) == visible_by_betweenness(now, event.robot)
                looks += 1
    assert engine.outcome != "collision" and looks > 100


def test_the_engine_and_every_file_refuse_points_outside_the_range():
    for robots in ([(0, 0), (-(2**63), 1), (3, 1)], [(0, 0), (10**23, 0)], [(0, 0), (L + 1, 0)]):
        with pytest.raises(EngineError, match="outside the supported range"):
            Engine(robots, [(0, 0), (1, 0), (2, 0)][: len(robots)], get_algorithm("stay"))
    text = '{"robots": [[0, 0], [1, 0], [100000000000000000000000, 5]]}'
    with pytest.raises(InputError) as err:
        parse_robots(text, "r.json")
    message = str(err.value)
    assert message.startswith("r.json: robot 2 at (~10^23, 5) is outside the supported range")
    assert f"{L:,}" in message and "\n" not in message
    with pytest.raises(InputError, match="pattern point 0 at"):
        parse_pattern(f'{{"points": [[{-L - 1}, 0]]}}', "p.json")
    header = (
        '{"format": "apf-viz-trace", "version": 1, "robots": [[0, 0], [0, 99999999999999999]], '
        '"pattern": [[0, 0], [1, 0]], "scheduler": "async", "algorithm": "stay"}'
    )
    with pytest.raises(InputError, match="robot 1 at"):
        parse_trace(header, "t.jsonl")
    huge = "9" * 5000  # more digits than Python turns into an int by default
    with pytest.raises(InputError, match="not valid JSON"):
        parse_robots(f'{{"robots": [[{huge}, 0]]}}', "r.json")
    with pytest.raises(InputError, match="nested too deeply"):
        parse_robots("[" * 100_000, "r.json")


def test_the_edges_of_the_range_are_accepted():
    corners = [(L, L), (-L, L), (L, -L), (-L, -L), (0, 0)]
    assert len(parse_robots(f'{{"robots": {[list(p) for p in corners]}}}', "r").robots) == 5
    engine = Engine(corners, [(0, 0), (0, 1), (0, 2), (0, 3), (0, 4)], get_algorithm("stay"))
    for i in range(5):
        assert engine.visible(i).tolist() == visible_by_betweenness(corners, i)


def test_a_run_translated_to_the_edge_of_the_range_is_the_same_run():
    start = [(0, 0), (3, 0), (5, 1), (2, 2), (6, 4), (1, 5)]
    pattern = [(0, 0), (1, 0), (2, 0), (0, 1), (1, 1), (2, 1)]
    y_up = [True, False, True, False, False, True]
    shift = (L - 40, -L + 40)
    far = [(x + shift[0], y + shift[1]) for x, y in start]
    runs = []
    for points in (start, far):
        engine = Engine(points, pattern, get_algorithm("apf-opaque-grid"), y_up=y_up, max_events=500_000)
        audit = audit_run(engine, "async", 5)
        assert audit.ok, audit.problems
        runs.append(engine)
    near_events, far_events = (e.history.events() for e in runs)
    assert len(near_events) == len(far_events) > 0
    for a, b in zip(near_events, far_events, strict=True):
        if a.phase == "move":
            assert b.to == (a.to[0] + shift[0], a.to[1] + shift[1])
        else:
            assert a == b


# ------------------------------------------------------------------------------------------ property tests
@st.composite
def far_configurations(draw):
    """A few robots anywhere in the range, some on common lines with big gaps (large gcds)."""
    coord = st.integers(-L, L)
    base = draw(st.lists(st.tuples(coord, coord), min_size=1, max_size=6))
    points = list(base)
    for _ in range(draw(st.integers(0, 5))):  # robots on a line through a robot, far along it
        x0, y0 = draw(st.sampled_from(points))
        d = draw(st.sampled_from([(1, 0), (0, 1), (1, 1), (1, -1), (2, 3), (-3, 7)]))
        t = draw(st.integers(-(10**11), 10**11))
        p = (x0 + t * d[0], y0 + t * d[1])
        if abs(p[0]) <= L and abs(p[1]) <= L:
            points.append(p)
    return list(dict.fromkeys(points))


@settings(max_examples=200, deadline=None)
@given(far_configurations())
def test_visibility_far_apart_equals_betweenness(points):
    arr = np.array(points, dtype=np.int64)
    for i in range(len(points)):
        assert visible_from(arr, i).tolist() == visible_by_betweenness(points, i)


@st.composite
def clusters_at_an_edge(draw):
    """A small cluster (lattice walks stay short) placed at a corner or edge of the range."""
    corner = (draw(st.sampled_from([-L, 0, L])), draw(st.sampled_from([-L, 0, L])))
    offsets = draw(
        st.lists(st.tuples(st.integers(0, 6), st.integers(0, 6)), min_size=1, max_size=14, unique=True)
    )
    sx = -1 if corner[0] > 0 else 1  # grow inwards
    sy = -1 if corner[1] > 0 else 1
    return [(corner[0] + sx * dx, corner[1] + sy * dy) for dx, dy in offsets]


@settings(max_examples=200, deadline=None)
@given(clusters_at_an_edge())
def test_visibility_at_the_edges_equals_the_lattice_walk(points):
    arr = np.array(points, dtype=np.int64)
    for i in range(len(points)):
        assert visible_from(arr, i).tolist() == sorted(visible_by_lattice_walk(points, i))


def view_from_scratch(points, lights, y_up, r):
    ids = visible_by_betweenness(points, r)
    x0, y0 = points[r]
    s = 1 if y_up[r] else -1
    return tuple(sorted(Seen(points[j][0] - x0, s * (points[j][1] - y0), lights[j]) for j in ids)), tuple(ids)


@settings(max_examples=150, deadline=None)
@given(far_configurations(), st.data())
def test_patched_views_far_apart_equal_views_from_scratch(points, data):
    """Moves next to robots far away: a vacated direction is searched without walking 10^11 points."""
    k = len(points)
    y_up = data.draw(st.lists(st.booleans(), min_size=k, max_size=k))
    lights = ["a"] * k
    positions = np.array(points, dtype=np.int64).reshape(k, 2)
    views = Views(positions, lights, y_up)
    for r in range(k):
        views.view(r)
    for _ in range(data.draw(st.integers(1, 8))):
        m = data.draw(st.integers(0, k - 1))
        step = data.draw(st.sampled_from([(1, 0), (-1, 0), (0, 1), (0, -1)]))
        current = [tuple(p) for p in positions.tolist()]
        new = (current[m][0] + step[0], current[m][1] + step[1])
        if new in current:
            continue
        positions[m] = new
        views.moved([m], [current[m]])
        now = [tuple(p) for p in positions.tolist()]
        for r in range(k):
            assert views.seen(r) == view_from_scratch(now, lights, y_up, r)
