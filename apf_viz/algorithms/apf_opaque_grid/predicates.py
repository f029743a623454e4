"""The paper's symbols (§2, *Notations and Definitions*) as predicates on one robot's local view.

Every function takes the :class:`~apf_viz.core.view.Snapshot` (the robot at the origin of its own frame)
and nothing else, so each is computable from the local view *by construction*. Where opacity could hide a
robot the docstring says why the answer is still exact (the notes' visibility facts):

- V1: in a convex region containing r, the robot nearest to r is visible, so "the region has a robot" is
  exact for half-planes and strips;
- V2: every robot on L_I(r) and R_I(r) is visible (the columns in between are empty);
- V3: on L_V(r) only the nearest robot above and the nearest below are visible.

The line K may fall between two grid rows, so K-related quantities use doubled y: ``k2 = 2·y_K``.

A snapshot lists its robots sorted by offset (dx, then dy), so the robots of one vertical line are a
contiguous run found by bisection: L_I, L_V and R_I cost O(log k), not a scan of the view.
"""

from __future__ import annotations

from bisect import bisect_left
from operator import itemgetter

from apf_viz.core.view import Seen, Snapshot

_light = itemgetter(2)


def others(view: Snapshot) -> tuple[Seen, ...]:
    return view.robots


def lights_of(robots: tuple[Seen, ...] | list[Seen]) -> set[str]:
    return set(map(_light, robots))


# ----------------------------------------------------------------------------------------- columns
_last_columns: tuple[Snapshot | None, tuple[list[Seen], list[Seen], list[Seen]]] = (None, ([], [], []))


def _columns(view: Snapshot) -> tuple[list[Seen], list[Seen], list[Seen]]:
    """(L_I, L_V, R_I) of this view by four bisections, kept for the last view asked about: one
    decision asks for them several times. (One tuple, read once: safe under threads.)"""
    global _last_columns
    last = _last_columns
    if last[0] is view:
        return last[1]
    robots = view.robots
    i0 = bisect_left(robots, (0,))
    i1 = bisect_left(robots, (1,), i0)
    left = list(robots[bisect_left(robots, (robots[i0 - 1].dx,), 0, i0) : i0]) if i0 else []
    right = list(robots[i1 : bisect_left(robots, (robots[i1].dx + 1,), i1)]) if i1 < len(robots) else []
    columns = (left, list(robots[i0:i1]), right)
    _last_columns = (view, columns)
    return columns


def vertical_line(view: Snapshot) -> list[Seen]:
    """L_V(r): the visible robots on r's own vertical line (at most the nearest above and below, V3)."""
    return _columns(view)[1]


def left_neighbour_line(view: Snapshot) -> list[Seen]:
    """L_I(r): the robots on the nearest occupied vertical line strictly left of r (all visible, V2)."""
    return _columns(view)[0]


def right_neighbour_line(view: Snapshot) -> list[Seen]:
    """R_I(r): the robots on the nearest occupied vertical line strictly right of r (all visible, V2)."""
    return _columns(view)[2]


def left_open_half_empty(view: Snapshot) -> bool:
    """H_L^O(r) = ∅: no robot strictly left of r (exact by V1). Equivalently, r is on L_1."""
    return not view.robots or view.robots[0].dx >= 0


def left_closed_half_has_other(view: Snapshot) -> bool:
    """H_L^C(r) ∖ {r} ≠ ∅: some robot with dx ≤ 0 (exact by V1)."""
    return bool(view.robots) and view.robots[0].dx <= 0


def upper_closed_half_has_other(view: Snapshot) -> bool:
    """H_U^C(r) ∖ {r} ≠ ∅: some robot with dy ≥ 0 in r's frame (exact by V1)."""
    return any(s.dy >= 0 for s in view.robots)


def bottom_closed_half_has_other(view: Snapshot) -> bool:
    """H_B^C(r) ∖ {r} ≠ ∅: some robot with dy ≤ 0 in r's frame (exact by V1)."""
    return any(s.dy <= 0 for s in view.robots)


def is_terminal(view: Snapshot) -> bool:
    """Terminal robot: L_V(r) ∩ H_U^O(r) = ∅ or L_V(r) ∩ H_B^O(r) = ∅ (the nearest ones are visible)."""
    column = vertical_line(view)
    return not (any(s.dy > 0 for s in column) and any(s.dy < 0 for s in column))


def is_singleton(view: Snapshot) -> bool:
    """r is alone on L_V(r)."""
    return not vertical_line(view)


def column_neighbour_with(view: Snapshot, lights: set[str]) -> Seen | None:
    """A visible robot on L_V(r) showing one of these lights (the nearest if both are)."""
    found = [s for s in vertical_line(view) if s.light in lights]
    return min(found, key=lambda s: abs(s.dy)) if found else None


# ----------------------------------------------------------------------------------------- K and λ
def k2_of(a: Seen, b: Seen | None = None) -> int:
    """Twice the y of K, the horizontal line through the midpoint of two robots on one vertical line
    (``b`` None: the second robot is r itself, at dy = 0)."""
    return a.dy + (b.dy if b is not None else 0)


def on_K(s: Seen, k2: int) -> bool:
    return 2 * s.dy == k2


def robot_on_K(line: list[Seen], k2: int) -> Seen | None:
    """The robot of this vertical line on K (K ∩ line), if any."""
    return next((s for s in line if on_K(s, k2)), None)


def _sides(line: list[Seen], k2: int) -> tuple[set[int], set[int]]:
    """Doubled distances from K of the robots above (U) and below (D) K on this line."""
    up = {2 * s.dy - k2 for s in line if 2 * s.dy > k2}
    down = {k2 - 2 * s.dy for s in line if 2 * s.dy < k2}
    return up, down


def is_symmetric_wrt_K(line: list[Seen], k2: int) -> bool:
    """λ₁ = λ₂: the line reads the same from K upwards and downwards (a robot on K is ignored; an empty
    line is symmetric)."""
    up, down = _sides(line, k2)
    return up == down


def dominant_side_is_up(line: list[Seen], k2: int) -> bool:
    """Which half of a non-symmetric line has the lexicographically larger λ: the one holding the
    robot nearest to K that has no mirror image."""
    up, down = _sides(line, k2)
    return min(up ^ down) in up


def in_dominant_half(view: Snapshot, k2: int) -> bool:
    """*Dominant half*: R_I(r) is not symmetric w.r.t. K, and r lies on the side of K whose λ is larger."""
    line = right_neighbour_line(view)
    if is_symmetric_wrt_K(line, k2) or k2 == 0:
        return False
    return dominant_side_is_up(line, k2) == (k2 < 0)


def closest_to_K(view: Snapshot, k2: int) -> bool:
    """r is the robot of L_V(r) closest to K (a robot on K makes every other robot not closest).

    Only r's visible neighbour towards K can be closer, so the answer is exact (V3)."""
    if k2 == 0:
        return True
    towards = [s for s in vertical_line(view) if (s.dy > 0) == (k2 > 0)]
    if not towards:
        return True
    n = towards[0]
    if on_K(n, k2) or abs(2 * n.dy) < abs(k2):  # the neighbour is on K or between r and K
        return False
    return abs(k2) <= abs(2 * n.dy - k2)
