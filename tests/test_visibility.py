"""Patched views (core/visibility.py) equal views computed from scratch with the lattice-walk oracle,
after any sequence of single moves, simultaneous moves and light changes."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from apf_viz.core import visibility
from apf_viz.core.view import Seen
from apf_viz.core.visibility import Views
from tests.oracle import visible_by_lattice_walk

LIGHTS = ("a", "b", "c")


def scratch_view(points, lights, y_up, r):
    """The oracle's view: walk every segment, then map to r's frame and sort."""
    ids = visible_by_lattice_walk(points, r)
    x0, y0 = points[r]
    s = 1 if y_up[r] else -1
    entries = sorted(Seen(points[j][0] - x0, s * (points[j][1] - y0), lights[j]) for j in ids)
    return tuple(entries), tuple(sorted(ids))


@st.composite
def scenarios(draw):
    pts = draw(
        st.lists(st.tuples(st.integers(-5, 5), st.integers(-5, 5)), min_size=1, max_size=25, unique=True)
    )
    k = len(pts)
    y_up = draw(st.lists(st.booleans(), min_size=k, max_size=k))
    lights = draw(st.lists(st.sampled_from(LIGHTS), min_size=k, max_size=k))
    ops = draw(
        st.lists(
            st.tuples(
                st.sampled_from(["move", "moves", "relit", "look"]),
                st.lists(st.integers(0, k - 1), min_size=1, max_size=4, unique=True),
                st.lists(st.sampled_from([(1, 0), (-1, 0), (0, 1), (0, -1), (0, 0)]), min_size=4, max_size=4),
                st.sampled_from(LIGHTS),
            ),
            max_size=30,
        )
    )
    return pts, y_up, lights, ops


@pytest.mark.parametrize("kernel", [False, True], ids=["numpy", "kernel"])
@settings(max_examples=300, deadline=None)
@given(scenarios())
def test_patched_views_equal_views_from_scratch(kernel, scenario):
    """With the numpy build, and with the compiled build (view_kernel.py) forced on for these few
    robots: the views are built either way, then patched the same way."""
    pts, y_up, lights, ops = scenario
    positions = np.array(pts, dtype=np.int64).reshape(len(pts), 2)
    lights = list(lights)
    with pytest.MonkeyPatch.context() as m:
        m.setattr(visibility, "KERNEL_MIN_ROBOTS", 1 if kernel else 10**9)
        views = Views(positions, lights, y_up)
    assert (views._kernel is not None) == kernel
    for r in range(len(pts)):  # build every observer so that every patch path runs
        views.view(r)
    for kind, robots, steps, light in ops:
        current = [tuple(p) for p in positions.tolist()]
        if kind == "relit":
            lights[robots[0]] = light
            views.relit(robots[0])
        elif kind in ("move", "moves"):
            movers = robots[:1] if kind == "move" else robots
            targets = {
                m: (current[m][0] + d[0], current[m][1] + d[1]) for m, d in zip(movers, steps, strict=False)
            }
            stay = set(range(len(pts))) - set(movers)
            final = [targets.get(i, current[i]) for i in range(len(pts))]
            if len(set(final)) != len(final) or any(final[i] != current[i] for i in stay):
                continue  # a collision: the engine would not apply it
            moved = [m for m in movers if targets[m] != current[m]]
            for m in moved:
                positions[m] = targets[m]
            if moved:
                views.moved(moved, [current[m] for m in moved])
        now = [tuple(p) for p in positions.tolist()]
        for r in range(len(pts)):
            assert views.seen(r) == scratch_view(now, lights, y_up, r), (kind, r)
        assert views.occupied == {p: i for i, p in enumerate(now)}


def test_a_move_reveals_the_robot_behind_and_hides_another():
    positions = np.array([(0, 0), (1, 0), (2, 0), (0, 2), (0, 1)], dtype=np.int64)
    lights = ["a"] * 5
    views = Views(positions, lights, [True] * 5)
    assert views.view(0)[1] == (1, 4)  # (2,0) is behind (1,0), (0,2) behind (0,1)
    old = (1, 0)
    positions[1] = (1, -1)
    views.moved([1], [old])
    assert views.view(0)[1] == (1, 2, 4)  # (2,0) comes into sight
    old = (0, 1)
    positions[4] = (1, 1)
    views.moved([4], [old])
    assert views.view(0)[1] == (1, 2, 3, 4)


def test_an_unchanged_view_returns_the_same_objects():
    positions = np.array([(0, 0), (3, 1), (5, 5)], dtype=np.int64)
    views = Views(positions, ["a"] * 3, [True, False, True])
    first = views.view(1)
    positions[2] = (6, 5)
    views.moved([2], [(5, 5)])
    assert views.view(0) is not None
    assert views.view(1)[1] is views.view(1)[1] and views.view(1)[0] is views.view(1)[0]
    assert views.seen(1)[0][0] == Seen(-3, 1, "a")  # robot 1's y is flipped
    assert first[0].entries()[0] == views.seen(1)[0][0]  # built as arrays, patched as entries
