"""The small starts an exhaustive search can cover: every start of a small box, and the curated
configurations of the implementers' notes (docs/VERIFICATION.md)."""

from __future__ import annotations

import itertools

from apf_viz.core.grid import Point
from apf_viz.core.pattern_match import mirror_y, normalise
from apf_viz.core.symmetry import unsolvable_axis

# The notes' configurations with k = 4 and 5 (docs/VERIFICATION.md, "Curated starts"): between them
# they reach the symmetric phase with its K shift, the K robot, and Phase 2's call/decider march, which
# no start of three robots reaches.
STATED_STARTS: dict[str, list[Point]] = {
    "C2 asymmetric R_I": [(0, 0), (0, 2), (1, 0), (1, 3)],
    "C5 one column": [(0, 0), (0, 1), (0, 2), (0, 4)],
    "C16 three on L_1": [(0, 0), (0, 1), (0, 2), (2, 4)],
    "C3 robot on K": [(0, 0), (0, 2), (1, 0), (1, 1), (1, 2)],
    "C6 symmetric, K shift": [(0, 0), (0, 2), (1, 0), (1, 2), (2, 5)],
    "C17 symmetric with K robot": [(0, 0), (0, 1), (0, 2), (1, 0), (1, 2)],
}


def box_starts(k: int, side: int = 4, mirrored: bool = False) -> list[list[Point]]:
    """Every set of k points of a side × side box, up to translation, in a fixed order.

    With ``mirrored``, also up to the mirror y → −y: a search over every assignment of flips sees the
    mirror image of a start as the start itself with every flip reversed (each robot's view is the
    same), so one of the two is enough. Not up to x → −x: the robots agree on right."""
    cells = [(x, y) for x in range(side) for y in range(side)]
    seen: set[tuple[Point, ...]] = set()
    out = []
    for pts in itertools.combinations(cells, k):
        key = normalise(pts)
        if key in seen or (mirrored and normalise(mirror_y(pts)) in seen):
            continue
        seen.add(key)
        out.append(list(key))
    return out


def solvable_box_starts(k: int, side: int = 4, mirrored: bool = False) -> list[list[Point]]:
    """:func:`box_starts` without the starts Theorem 1 proves unsolvable."""
    return [s for s in box_starts(k, side, mirrored) if unsolvable_axis(s) is None]


def line_pattern(k: int) -> list[Point]:
    """The pattern the small-start searches form: k robots in a row."""
    return [(i, 0) for i in range(k)]


def axis_symmetric(points: list[Point]) -> bool:
    """Mirror-symmetric about a horizontal line through at least one robot: solvable (Theorem 1), and
    the starts whose leader election needs Phase 1's symmetric case, K and the robots on it."""
    ys = [y for _, y in points]
    c2 = min(ys) + max(ys)
    cells = set(points)
    return any(2 * y == c2 for y in ys) and all((x, c2 - y) in cells for x, y in points)


def axis_symmetric_box_starts(k: int, side: int = 5) -> list[list[Point]]:
    """Every start of k robots in a side × side box that is symmetric with robots on its axis, up to
    translation (a mirror image is the start itself): 4, 24, 56 and 182 of k = 2 … 5 in a 5×5 box."""
    return [s for s in box_starts(k, side, mirrored=True) if axis_symmetric(s)]
