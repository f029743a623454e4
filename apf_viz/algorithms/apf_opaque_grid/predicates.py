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

from operator import itemgetter

from apf_viz.core.portrayal import NO_EVIDENCE, Evidence, HalfPlane, Line
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
    n = len(view)
    i0 = view.column_start(0)
    i1 = view.column_start(1, i0)
    left = list(view.between(view.column_start(view.dx_at(i0 - 1)), i0)) if i0 else []
    right = list(view.between(i1, view.column_start(view.dx_at(i1) + 1, i1))) if i1 < n else []
    columns = (left, list(view.between(i0, i1)), right)
    _last_columns = (view, columns)
    return columns


def _lights_text(robots: list[Seen]) -> str:
    return ", ".join(s.light for s in robots) if robots else "none"


def vertical_line(view: Snapshot, ev: Evidence = NO_EVIDENCE) -> list[Seen]:
    """L_V(r): the visible robots on r's own vertical line (at most the nearest above and below, V3)."""
    column = _columns(view)[1]
    if ev.active:
        ev.region(Line("x", 0, "L_V"))
        ev.test("L_V(r)", _lights_text(column), "the robots I see on my own vertical line")
    return column


def left_neighbour_line(view: Snapshot, ev: Evidence = NO_EVIDENCE) -> list[Seen]:
    """L_I(r): the robots on the nearest occupied vertical line strictly left of r (all visible, V2)."""
    return _neighbour_line(view, 0, "L_I", "left", ev)


def right_neighbour_line(view: Snapshot, ev: Evidence = NO_EVIDENCE) -> list[Seen]:
    """R_I(r): the robots on the nearest occupied vertical line strictly right of r (all visible, V2)."""
    return _neighbour_line(view, 2, "R_I", "right", ev)


def _neighbour_line(view: Snapshot, which: int, name: str, side: str, ev: Evidence) -> list[Seen]:
    line = _columns(view)[which]
    if ev.active:
        if line:
            ev.region(Line("x", line[0].dx, name))
        ev.test(f"{name}(r)", _lights_text(line), f"the robots on the nearest occupied line to my {side}")
    return line


def left_open_half_empty(view: Snapshot, ev: Evidence = NO_EVIDENCE) -> bool:
    """H_L^O(r) = ∅: no robot strictly left of r (exact by V1). Equivalently, r is on L_1."""
    value = not len(view) or view.dx_at(0) >= 0
    if ev.active:
        ev.region(HalfPlane("x", 0, -1, False, "H_L^O"))
        ev.test("H_L^O(r) = ∅", value, "no robot strictly left of me, in the open half-plane (I am on L_1)")
    return value


def left_closed_half_has_other(view: Snapshot, ev: Evidence = NO_EVIDENCE) -> bool:
    """H_L^C(r) ∖ {r} ≠ ∅: some robot with dx ≤ 0 (exact by V1)."""
    value = bool(len(view)) and view.dx_at(0) <= 0
    if ev.active:
        ev.region(HalfPlane("x", 0, -1, True, "H_L^C"))
        ev.test("H_L^C(r) ∖ {r} ≠ ∅", value, "another robot on my line or to its left (closed half-plane)")
    return value


def upper_closed_half_has_other(view: Snapshot, ev: Evidence = NO_EVIDENCE) -> bool:
    """H_U^C(r) ∖ {r} ≠ ∅: some robot with dy ≥ 0 in r's frame (exact by V1)."""
    value = any(s.dy >= 0 for s in view.robots)
    if ev.active:
        ev.region(HalfPlane("y", 0, 1, True, "H_U^C"))
        ev.test("H_U^C(r) ∖ {r} ≠ ∅", value, "another robot on my row or above it (my own +y)")
    return value


def bottom_closed_half_has_other(view: Snapshot, ev: Evidence = NO_EVIDENCE) -> bool:
    """H_B^C(r) ∖ {r} ≠ ∅: some robot with dy ≤ 0 in r's frame (exact by V1)."""
    value = any(s.dy <= 0 for s in view.robots)
    if ev.active:
        ev.region(HalfPlane("y", 0, -1, True, "H_B^C"))
        ev.test("H_B^C(r) ∖ {r} ≠ ∅", value, "another robot on my row or below it (my own −y)")
    return value


def is_terminal(view: Snapshot, ev: Evidence = NO_EVIDENCE) -> bool:
    """Terminal robot: L_V(r) ∩ H_U^O(r) = ∅ or L_V(r) ∩ H_B^O(r) = ∅ (the nearest ones are visible)."""
    column = vertical_line(view)
    value = not (any(s.dy > 0 for s in column) and any(s.dy < 0 for s in column))
    if ev.active:
        ev.region(Line("x", 0, "L_V"))
        ev.test("r is terminal", value, "no robot above me or none below me on L_V")
    return value


def is_singleton(view: Snapshot, ev: Evidence = NO_EVIDENCE) -> bool:
    """r is alone on L_V(r)."""
    value = not vertical_line(view)
    if ev.active:
        ev.region(Line("x", 0, "L_V"))
        ev.test("L_V(r) = {r}", value, "I am alone on my vertical line")
    return value


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


def robot_on_K(line: list[Seen], k2: int, ev: Evidence = NO_EVIDENCE, name: str = "R_I") -> Seen | None:
    """The robot of this vertical line on K (K ∩ line), if any."""
    found = next((s for s in line if on_K(s, k2)), None)
    if ev.active:
        mark_K(ev, k2)
        ev.test(f"K ∩ {name} = ∅", found is None, f"no robot of {name} lies on K")
    return found


def mark_K(ev: Evidence, k2: int) -> None:
    """K as a region (it may pass between two rows)."""
    ev.region(Line("y", k2 / 2, "K"))


def _sides(line: list[Seen], k2: int) -> tuple[set[int], set[int]]:
    """Doubled distances from K of the robots above (U) and below (D) K on this line."""
    up = {2 * s.dy - k2 for s in line if 2 * s.dy > k2}
    down = {k2 - 2 * s.dy for s in line if 2 * s.dy < k2}
    return up, down


def is_symmetric_wrt_K(line: list[Seen], k2: int, ev: Evidence = NO_EVIDENCE, name: str = "R_I") -> bool:
    """λ₁ = λ₂: the line reads the same from K upwards and downwards (a robot on K is ignored; an empty
    line is symmetric)."""
    up, down = _sides(line, k2)
    if ev.active:
        mark_K(ev, k2)
        ev.test(
            f"{name} symmetric w.r.t. K (λ₁ = λ₂)", up == down, f"{name} reads the same up and down from K"
        )
    return up == down


def dominant_side_is_up(line: list[Seen], k2: int) -> bool:
    """Which half of a non-symmetric line has the lexicographically larger λ: the one holding the
    robot nearest to K that has no mirror image."""
    up, down = _sides(line, k2)
    return min(up ^ down) in up


def in_dominant_half(view: Snapshot, k2: int, ev: Evidence = NO_EVIDENCE) -> bool:
    """*Dominant half*: R_I(r) is not symmetric w.r.t. K, and r lies on the side of K whose λ is larger."""
    line = right_neighbour_line(view)
    value = not (is_symmetric_wrt_K(line, k2) or k2 == 0) and dominant_side_is_up(line, k2) == (k2 < 0)
    if ev.active:
        mark_K(ev, k2)
        ev.region(HalfPlane("y", k2 / 2, -1 if k2 > 0 else 1, False, "my side of K"))
        ev.test(
            "r in the dominant half", value, "R_I is asymmetric about K and my side of K has the larger λ"
        )
    return value


def closest_to_K(view: Snapshot, k2: int, ev: Evidence = NO_EVIDENCE) -> bool:
    """r is the robot of L_V(r) closest to K (a robot on K makes every other robot not closest).

    Only r's visible neighbour towards K can be closer, so the answer is exact (V3)."""
    value = _closest_to_K(view, k2)
    if ev.active:
        mark_K(ev, k2)
        ev.region(Line("x", 0, "L_V"))
        ev.test("r closest to K on L_V", value, "no robot of my vertical line is nearer to K than I am")
    return value


def _closest_to_K(view: Snapshot, k2: int) -> bool:
    if k2 == 0:
        return True
    towards = [s for s in vertical_line(view) if (s.dy > 0) == (k2 > 0)]
    if not towards:
        return True
    n = towards[0]
    if on_K(n, k2) or abs(2 * n.dy) < abs(k2):  # the neighbour is on K or between r and K
        return False
    return abs(k2) <= abs(2 * n.dy - k2)
