"""Visibility: the O(k) nearest-per-direction Look equals the lattice-walk oracle."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from apf_viz.core.grid import Direction, hiders, visible_from
from tests.oracle import visible_by_lattice_walk

points_sets = st.sets(st.tuples(st.integers(-6, 6), st.integers(-6, 6)), min_size=1, max_size=40)


@settings(max_examples=300, deadline=None)
@given(points_sets, st.data())
def test_visibility_equals_oracle(points, data):
    pts = sorted(points)
    i = data.draw(st.integers(0, len(pts) - 1))
    fast = visible_from(np.array(pts, dtype=np.int64), i).tolist()
    assert fast == visible_by_lattice_walk(pts, i)


@settings(max_examples=50, deadline=None)
@given(st.sets(st.tuples(st.integers(-1000, 1000), st.integers(-1000, 1000)), min_size=2, max_size=30))
def test_visibility_equals_oracle_on_a_wide_grid(points):
    pts = sorted(points)
    for i in range(len(pts)):
        assert visible_from(np.array(pts), i).tolist() == visible_by_lattice_walk(pts, i)


def test_a_robot_hides_the_ones_behind_it():
    pts = [(0, 0), (1, 0), (2, 0), (2, 1), (4, 2), (0, 5)]
    # (2,0) is behind (1,0); (4,2) is behind (2,1); (0,5) is in plain view.
    assert visible_from(np.array(pts), 0).tolist() == [1, 3, 5]


def test_visibility_is_symmetric_between_two_robots():
    pts = [(0, 0), (3, 6), (1, 2), (5, 1)]
    arr = np.array(pts)
    for i in range(len(pts)):
        for j in visible_from(arr, i).tolist():
            assert i in visible_from(arr, j).tolist()


def test_direction_deltas_round_trip():
    for d in Direction:
        assert Direction.from_delta(*d.delta) is d


@settings(max_examples=30, deadline=None)
@given(
    st.sets(st.tuples(st.integers(-(2**22), 2**22), st.integers(-(2**22), 2**22)), min_size=2, max_size=12)
)
def test_visibility_equals_oracle_beyond_the_packed_key_range(points):
    pts = sorted(points)
    for i in range(len(pts)):
        assert visible_from(np.array(pts), i).tolist() == visible_by_lattice_walk(pts, i)


def test_the_direction_tables_give_the_same_visible_robots_as_gcds(monkeypatch):
    import random

    import apf_viz.core.grid as grid

    rng = random.Random(4)
    for _ in range(100):
        side = rng.choice([3, 10, 90])
        points = rng.sample(
            [(x, y) for x in range(-side, side) for y in range(-side, side)],
            rng.randint(2, min(40, 4 * side * side)),
        )
        offsets = np.array(points, dtype=np.int64) - np.array(points[0], dtype=np.int64)
        tables = grid.nearest_per_direction(offsets, 0).tolist()
        monkeypatch.setattr(grid, "TABLE_SPAN", 0)
        assert grid.nearest_per_direction(offsets, 0).tolist() == tables
        monkeypatch.undo()


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(st.integers(-12, 12), st.integers(-12, 12)), min_size=1, max_size=40, unique=True))
def test_visible_in_a_crowd_by_minimum_per_direction_equals_the_lattice_walk(points):
    from apf_viz.core.grid import table_index, table_scratch, visible_in_crowd

    scratch = table_scratch()
    arr = np.array(points, dtype=np.int64)
    for i in range(len(points)):
        visible = visible_in_crowd(table_index(arr - arr[i]), i, scratch)
        assert visible.tolist() == sorted(visible_by_lattice_walk(points, i))
    assert (scratch == np.iinfo(np.int64).max).all()  # left as it was found


@given(points_sets, st.data())
def test_each_hidden_robot_is_hidden_by_a_visible_robot_on_its_segment(points, data):
    pts = sorted(points)
    i = data.draw(st.integers(0, len(pts) - 1))
    hidden = hiders(pts, i)
    seen = set(visible_by_lattice_walk(pts, i))
    assert set(hidden) == set(range(len(pts))) - seen - {i}
    (x0, y0) = pts[i]
    for j, h in hidden.items():
        assert h in seen
        (xh, yh), (xj, yj) = pts[h], pts[j]
        assert (xh - x0) * (yj - y0) == (yh - y0) * (xj - x0)  # on the line of sight
        assert 0 < (xh - x0) * (xj - x0) + (yh - y0) * (yj - y0) < (xj - x0) ** 2 + (yj - y0) ** 2  # between
