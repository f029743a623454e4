"""Algorithm 2, *Phase 2* ("leader selection"): from a stable configuration or a leader1 robot to a
leader configuration."""

from __future__ import annotations

from apf_viz.algorithms.apf_opaque_grid.phase1 import away_from, stay
from apf_viz.algorithms.apf_opaque_grid.predicates import (
    bottom_closed_half_has_other,
    closest_to_K,
    column_neighbour_with,
    dominant_side_is_up,
    in_dominant_half,
    is_singleton,
    is_symmetric_wrt_K,
    is_terminal,
    k2_of,
    left_closed_half_has_other,
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


def two_deciders_on_left_line(view: Snapshot) -> bool:
    """The Phase-2 trigger for an off robot: L_I(r) holds exactly two decider robots."""
    return sum(1 for s in left_neighbour_line(view) if s.light == "decider") == 2


def phase2_decider(view: Snapshot, res: frozenset[str]) -> Decision:
    """Algorithm 2, r.light = decider (lines 3–22)."""
    if "L2" in res and _lone_decider(view):
        return Decision("leader1", None, "decider (L2): no other decider, nothing to my left → leader1 again")
    r_i = right_neighbour_line(view)
    column = vertical_line(view)
    if "leader1" in lights_of(r_i) | lights_of(column):
        return Decision("off", None, "Phase 2 (decider): a leader1 on R_I or L_V → off")
    partner = column_neighbour_with(view, {"decider"})
    if partner is not None:
        k2 = k2_of(partner)
        if robot_on_K(r_i, k2) is None:
            if is_symmetric_wrt_K(r_i, k2):
                if all(s.light == "call" for s in r_i):
                    return Decision(
                        "decider",
                        Direction.RIGHT,
                        "Phase 2 (decider): R_I symmetric and all call → move right",
                    )
                return stay(view, "Phase 2 (decider): R_I symmetric → wait until all of R_I is call")
            if in_dominant_half(view, k2):
                return Decision(
                    "leader1", None, "Phase 2 (decider): R_I asymmetric, I am in the dominant half → leader1"
                )
            return stay(view, "Phase 2 (decider): R_I asymmetric, the other decider is dominant → wait")
    if "decider" in lights_of(r_i):
        return Decision(
            "decider", Direction.RIGHT, "Phase 2 (decider): the other decider is on R_I → move right"
        )
    l_i = left_neighbour_line(view)
    if (
        "call" in lights_of(column)
        and "decider" not in lights_of(l_i)
        and all(s.light == "call" for s in r_i)
    ):
        return Decision(
            "decider",
            Direction.RIGHT,
            "Phase 2 (decider): call on L_V, no decider on L_I, all of R_I call → move right",
        )
    return stay(view, "Phase 2 (decider): waiting (a robot on K ∩ R_I, or the other decider)")


def _lone_decider(view: Snapshot) -> bool:
    """L2's other half: a decider made from a leader1 whose partner turned off instead sees no decider
    anywhere, nothing to its left, and only off robots on its own line (a partner still symmetric is on
    its way to becoming a decider; deciders hidden from each other by call robots, B12, see those)."""
    return (
        left_open_half_empty(view)
        and "decider" not in lights_of(view.robots)
        and lights_of(vertical_line(view)) <= {"off"}
    )


def phase2_off(view: Snapshot, res: frozenset[str]) -> Decision:
    """Algorithm 2, r.light = off, with two deciders on L_I(r) (lines 23–35)."""
    a, b = (s for s in left_neighbour_line(view) if s.light == "decider")
    k2 = k2_of(a, b)
    r_i = right_neighbour_line(view)
    symmetric = is_symmetric_wrt_K(r_i, k2)
    if k2 == 0:
        if "KD" in res and not symmetric:
            up = dominant_side_is_up(r_i, k2)
            if any((s.dy > 0) == up for s in vertical_line(view)):
                return stay(
                    view, "Phase 2 (off): on K, but a robot of L_V is on the dominant side → defer (KD)"
                )
        return Decision("leader1", None, "Phase 2 (off): two deciders on L_I and I am on K → leader1")
    if symmetric:
        if closest_to_K(view, k2) or "call" in lights_of(vertical_line(view)):
            return Decision(
                "call", None, "Phase 2 (off): R_I symmetric, I am closest to K (or see call) → call"
            )
        return stay(view, "Phase 2 (off): R_I symmetric, not closest to K → wait")
    if is_terminal(view) and in_dominant_half(view, k2):
        return Decision(
            "leader1", None, "Phase 2 (off): R_I asymmetric, terminal in the dominant half → leader1"
        )
    return stay(view, "Phase 2 (off): R_I asymmetric, not the dominant terminal → wait")


def phase2_call(view: Snapshot, res: frozenset[str]) -> Decision:
    """Algorithm 2, r.light = call (lines 36–38)."""
    if "G3" in res:
        seen = lights_of(view.robots)
        if seen & {"leader1", "leader"}:
            return Decision("off", None, "Phase 2 (call): a leader1/leader is visible → off (G3)")
    elif "leader1" in lights_of(right_neighbour_line(view)) | lights_of(left_neighbour_line(view)):
        return Decision("off", None, "Phase 2 (call): a leader1 on R_I or L_I → off")
    return stay(view, "Phase 2 (call): waiting for a leader1")


def two_leader1_become_deciders(view: Snapshot) -> Decision | None:
    """L2 (found by the explorer, docs/VERIFICATION.md): two leader1 robots on one leftmost line (one
    promoted on a stale view) would walk left in lockstep forever. Settle them the way the paper settles two
    robots on L_1: with R_I symmetric about their K they take the symmetric light and move apart to
    extreme rows first (the paper's argument that this cannot create a symmetry needs R_I symmetric);
    otherwise they become the two deciders and Phase 2 elects among them and the rest. A robot that
    changes light while its partner is still leader1 turns off on seeing it (G2 / the decider rule), which
    leaves one leader1; a decider left alone becomes leader1 again (:func:`_lone_decider`)."""
    partner = column_neighbour_with(view, {"leader1"})
    if partner is None or not left_open_half_empty(view):
        return None
    extreme = not (upper_closed_half_has_other(view) and bottom_closed_half_has_other(view))
    r_i = right_neighbour_line(view)
    k2 = k2_of(partner)
    if not extreme and robot_on_K(r_i, k2) is None and is_symmetric_wrt_K(r_i, k2):
        return Decision("symmetric", None, "leader1 (L2): another leader1 on L_V, R_I symmetric → symmetric")
    return Decision("decider", None, "leader1 (L2): another leader1 on L_V → decider")


def phase2_leader1(view: Snapshot, res: frozenset[str]) -> Decision:
    """Algorithm 2, r.light = leader1 (lines 39–58)."""
    if "L2" in res:
        if column_neighbour_with(view, {"terminal1", "symmetric"}) is not None:
            # It may be promoted on a view older than my light (B3): moving now could make the
            # configuration symmetric; it turns off on seeing me (G2), or we settle as two leader1.
            return stay(view, "leader1 (L2): a terminal1/symmetric robot on L_V → wait for it to settle")
        settled = two_leader1_become_deciders(view)
        if settled is not None:
            return settled
    l_i = left_neighbour_line(view)
    r_i = right_neighbour_line(view)
    left_all_off = all(s.light == "off" for s in l_i) and ("NV" not in res or bool(l_i))
    may_act = left_all_off or (left_open_half_empty(view) and all(s.light == "off" for s in r_i))
    if may_act:
        upper, bottom = upper_closed_half_has_other(view), bottom_closed_half_has_other(view)
        if not upper or not bottom:
            if left_closed_half_has_other(view):
                return Decision(
                    "leader1",
                    Direction.LEFT,
                    "Phase 2 (leader1): an extreme row, H_L^C not empty → move left",
                )
            return Decision("leader", None, "Phase 2 (leader1): H_L^C empty and an extreme row → leader")
        if not is_terminal(view):
            return Decision("leader1", Direction.LEFT, "Phase 2 (leader1): not terminal on L_V → move left")
        if not is_singleton(view):
            (neighbour,) = vertical_line(view)
            return Decision(
                "leader1",
                away_from(neighbour.dy),
                "Phase 2 (leader1): terminal, not alone on L_V → move away from r′",
            )
        if "SD" in res and r_i and (all(s.dy > 0 for s in r_i) or all(s.dy < 0 for s in r_i)):
            return Decision(
                "leader1", away_from(r_i[0].dy), "Phase 2 (leader1): alone on L_V → move away from R_I (SD)"
            )
        return Decision("leader1", Direction.UP, "Phase 2 (leader1): alone on L_V → move along my +y")
    if "leader1" in lights_of(l_i):
        return Decision("off", None, "Phase 2 (leader1): another leader1 on L_I → off")
    return stay(view, "Phase 2 (leader1): waiting for L_I (or R_I) to turn off")
