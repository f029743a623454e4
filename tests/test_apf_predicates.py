"""The paper's symbols as predicates on a local view (docs/ALGORITHM.md, "Predicates")."""

from __future__ import annotations

from apf_viz.algorithms.apf_opaque_grid import LIGHTS, ApfOpaqueGrid, embedded_targets
from apf_viz.algorithms.apf_opaque_grid.predicates import (
    closest_to_K,
    dominant_side_is_up,
    in_dominant_half,
    is_singleton,
    is_symmetric_wrt_K,
    is_terminal,
    left_neighbour_line,
    left_open_half_empty,
    right_neighbour_line,
)
from apf_viz.core.view import Seen, Snapshot


def view(*robots: tuple[int, int, str], light: str = "off") -> Snapshot:
    return Snapshot(light, tuple(sorted(Seen(*r) for r in robots)))


def col(x: int, *ys: int) -> list[Seen]:
    return [Seen(x, y, "off") for y in ys]


def test_exactly_the_papers_eight_lights():
    assert LIGHTS == ("off", "terminal1", "symmetric", "decider", "call", "leader1", "leader", "done")
    assert ApfOpaqueGrid().lights == LIGHTS


def test_neighbour_lines_and_halves():
    v = view((-3, 1, "off"), (-1, 2, "off"), (-1, -4, "decider"), (2, 0, "off"), (5, 5, "off"), (0, 3, "off"))
    assert {(s.dx, s.dy) for s in left_neighbour_line(v)} == {(-1, 2), (-1, -4)}
    assert [(s.dx, s.dy) for s in right_neighbour_line(v)] == [(2, 0)]
    assert not left_open_half_empty(v)
    assert is_terminal(v) and not is_singleton(v)
    assert not is_terminal(view((0, 1, "off"), (0, -2, "off")))
    assert left_open_half_empty(view((0, 1, "off"), (3, -2, "off")))


def test_symmetry_of_a_line_wrt_K_on_a_row_and_between_rows():
    # K on row y = 1 (k2 = 2): robots at 0 and 2 mirror each other; the one on K is ignored.
    assert is_symmetric_wrt_K(col(1, 0, 1, 2), 2)
    assert not is_symmetric_wrt_K(col(1, 0, 3), 2)
    # K between rows (k2 = 1, y = 0.5): 0 and 1 mirror each other.
    assert is_symmetric_wrt_K(col(1, 0, 1, -1, 2), 1)
    assert is_symmetric_wrt_K([], 5)  # an empty line is symmetric


def test_dominant_side_is_the_one_with_the_nearest_unmatched_robot():
    # K at y = 1: above at distance 2 (y = 3), below at distance 1 (y = 0): below dominates.
    assert not dominant_side_is_up(col(1, 0, 3), 2)
    assert dominant_side_is_up(col(1, 2, -1, 4), 2)  # distances: up 1, 3; down 3 → up (1 unmatched)


def test_in_dominant_half_is_relative_to_R_I():
    # r at origin, its partner at dy = 2: K at y = 1 (k2 = 2). R_I at dx = 1 with robots at dy 0 and 3.
    v = view((0, 2, "terminal1"), (1, 0, "off"), (1, 3, "off"), light="terminal1")
    assert in_dominant_half(v, 2)  # below K and the lower side dominates
    flipped = view((0, -2, "terminal1"), (1, 0, "off"), (1, -3, "off"), light="terminal1")
    assert in_dominant_half(flipped, -2)  # the same seen by a robot whose y-axis is flipped


def test_closest_to_K():
    # K at y = 2 (k2 = 4). r at 0; its neighbour above at 1 lies between r and K: r is not closest.
    assert not closest_to_K(view((0, 1, "off")), 4)
    # neighbour beyond K at y = 5: distance 3 > 2, r is closest.
    assert closest_to_K(view((0, 5, "off")), 4)
    # neighbour on K: nobody else is closest.
    assert not closest_to_K(view((0, 2, "off")), 4)
    # no neighbour towards K.
    assert closest_to_K(view((0, -1, "off")), 4)


def test_pattern_embedding_and_order():
    targets = embedded_targets(((5, 5), (6, 5), (5, 7), (8, 6)))
    assert min(y for _, y in targets) == 1 and min(x for x, _ in targets) == 0
    # top row first, right to left within a row; t_{n-1} is the bottom-left point.
    assert targets == ((0, 3), (3, 2), (1, 1), (0, 1))
