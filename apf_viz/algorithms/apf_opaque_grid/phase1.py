"""Algorithm 1, *Phase 1*: from the start to a stable configuration or one robot with light leader1."""

from __future__ import annotations

from apf_viz.algorithms.apf_opaque_grid.predicates import (
    bottom_closed_half_has_other,
    column_neighbour_with,
    in_dominant_half,
    is_singleton,
    is_symmetric_wrt_K,
    is_terminal,
    k2_of,
    left_neighbour_line,
    left_open_half_empty,
    lights_of,
    right_neighbour_line,
    robot_on_K,
    upper_closed_half_has_other,
    vertical_line,
)
from apf_viz.core.algorithm import Decision
from apf_viz.core.grid import Direction
from apf_viz.core.view import Snapshot


def stay(view: Snapshot, rule: str) -> Decision:
    return Decision(view.light, None, rule)


def away_from(dy: int) -> Direction:
    """'Move vertically opposite to r′' for a column neighbour at this dy."""
    return Direction.DOWN if dy > 0 else Direction.UP


def phase1_off(view: Snapshot, res: frozenset[str]) -> Decision:
    """Algorithm 1, r.light = off (lines 3–7)."""
    r_i = right_neighbour_line(view)
    if is_terminal(view) and left_open_half_empty(view) and "leader1" not in lights_of(r_i):
        return Decision(
            "terminal1",
            Direction.LEFT,
            "Phase 1 (off): terminal, H_L^O empty, no leader1 on R_I → terminal1, move left",
        )
    l_i = left_neighbour_line(view)
    terminals = [s for s in l_i if s.light == "terminal1"]
    exactly_two = len(terminals) == 2 and ("E2" not in res or len(l_i) == 2)
    if exactly_two and k2_of(terminals[0], terminals[1]) == 0:
        return Decision("leader1", None, "Phase 1 (off): two terminal1 on L_I and I am on K → leader1")
    return stay(view, "Phase 1 (off): no rule applies → wait")


def phase1_terminal1(view: Snapshot, res: frozenset[str]) -> Decision:
    """Algorithm 1, r.light = terminal1 (lines 8–24)."""
    partner = column_neighbour_with(view, {"terminal1"})
    r_i = right_neighbour_line(view)
    if partner is not None:
        k2 = k2_of(partner)
        on_k = robot_on_K(r_i, k2)
        if on_k is None:
            if is_symmetric_wrt_K(r_i, k2):
                return Decision(
                    "symmetric", None, "Phase 1 (terminal1): K ∩ R_I empty, R_I symmetric → symmetric"
                )
            if in_dominant_half(view, k2):
                return Decision(
                    "leader1",
                    None,
                    "Phase 1 (terminal1): R_I asymmetric, I am in the dominant half → leader1",
                )
            return stay(view, "Phase 1 (terminal1): R_I asymmetric, I am not in the dominant half → wait")
        if on_k.light == "leader1":
            return Decision("off", None, "Phase 1 (terminal1): the robot on K ∩ R_I is leader1 → off")
        return stay(view, "Phase 1 (terminal1): a robot is on K ∩ R_I → wait for it to become leader1")
    column = lights_of(vertical_line(view))
    if "symmetric" in column:
        return Decision("symmetric", None, "Phase 1 (terminal1): a symmetric robot on L_V → symmetric")
    if column & {"leader1", "off"}:
        return Decision("off", None, "Phase 1 (terminal1): a leader1 or off robot on L_V → off")
    if is_singleton(view) and all(s.light == "off" for s in r_i):
        return Decision("leader1", None, "Phase 1 (terminal1): alone on L_V, all of R_I off → leader1")
    return stay(view, "Phase 1 (terminal1): waiting for the other terminal1")


def phase1_symmetric(view: Snapshot, res: frozenset[str]) -> Decision:
    """Algorithm 1, r.light = symmetric (lines 25–31)."""
    partner = column_neighbour_with(view, {"symmetric", "decider"})
    if partner is None:
        return stay(view, "Phase 1 (symmetric): no symmetric/decider robot on L_V → wait")
    if upper_closed_half_has_other(view) and bottom_closed_half_has_other(view):
        return Decision(
            "symmetric",
            away_from(partner.dy),
            "Phase 1 (symmetric): others in H_U^C and H_B^C → move away from r′",
        )
    return Decision("decider", None, "Phase 1 (symmetric): H_U^C or H_B^C empty → decider")
