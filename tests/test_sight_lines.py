"""The explorer's views of a crowd, read off one numpy pass for every robot (``sight_lines``), are the
per-robot lattice walk's (``visible``), in both orders a robot's y-axis can give; and a search that uses
them reaches the verdicts and state counts of one that does not."""

from __future__ import annotations

import random

import pytest

from apf_viz.algorithms import get_algorithm
from apf_viz.explore import state_space
from apf_viz.explore.explorer import Explorer
from apf_viz.explore.hunt_families import draw
from apf_viz.explore.state_space import sight_lines, visible


def test_sight_lines_are_the_nearest_robot_of_every_direction_in_both_orders():
    rng = random.Random(1)
    for _ in range(400):
        k, w = rng.randint(2, 45), rng.choice([7, 12, 40, 1000])
        cells: set[tuple[int, int]] = set()
        while len(cells) < k:
            cells.add((rng.randrange(w), rng.randrange(w)))
        pts = list(cells)
        lines = sight_lines([v for p in pts for v in p])
        for r in range(k):
            dx, dy, who, flipped = lines[r]
            for s in (1, -1):
                want = sorted(
                    (pts[j][0] - pts[r][0], s * (pts[j][1] - pts[r][1]), j) for j in visible(pts, r)
                )
                up = list(zip(dx, dy, who, strict=True))
                got = up if s == 1 else [(dx[i], -dy[i], who[i]) for i in flipped]
                assert got == want


@pytest.mark.parametrize(("family", "k", "seed"), [("dense", 9, 1), ("tall", 10, 2), ("wide-pattern", 8, 0)])
def test_a_search_reads_the_same_views_either_way(family, k, seed, monkeypatch):
    case = draw(family, k, seed)
    algo = get_algorithm("apf-opaque-grid")

    def search():
        return Explorer(algo, case.robots, case.pattern, case.y_up, reduction=True, eligible_only=True).run()

    fast = search()
    monkeypatch.setattr(state_space, "SIGHT_LINES_FROM", 10**6)
    plain = search()
    assert (fast.verdict, fast.states, fast.transitions) == (plain.verdict, plain.states, plain.transitions)
