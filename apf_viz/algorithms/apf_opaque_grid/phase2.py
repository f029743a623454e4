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
    mark_K,
    right_neighbour_line,
    robot_on_K,
    upper_closed_half_has_other,
    vertical_line,
)
from apf_viz.algorithms.apf_opaque_grid.resolutions import G3, G5, KD, L2, NV, SD, Resolutions, deviation
from apf_viz.algorithms.apf_opaque_grid.strides import FOREVER, left_walk_stride, vertical_stride
from apf_viz.core.algorithm import Decision
from apf_viz.core.grid import Direction
from apf_viz.core.portrayal import NO_EVIDENCE, Evidence
from apf_viz.core.view import Seen, Snapshot


def two_deciders_on_left_line(view: Snapshot) -> bool:
    """The Phase-2 trigger for an off robot: L_I(r) holds exactly two decider robots."""
    return sum(1 for s in left_neighbour_line(view) if s.light == "decider") == 2


def phase2_decider(view: Snapshot, res: Resolutions, ev: Evidence = NO_EVIDENCE) -> Decision:
    """Algorithm 2, r.light = decider (lines 3–22)."""
    if L2 in res and deviation(ev, L2, _lone_decider(view, ev)):
        return Decision(
            "leader1",
            None,
            "decider (L2): no other decider, nothing to my left → leader1 again",
            "A2.decider.L2-alone",
        )
    r_i = right_neighbour_line(view, ev)
    column = vertical_line(view, ev)
    if ev.test(
        "a leader1 on R_I or L_V", "leader1" in lights_of(r_i) | lights_of(column), "a robot elected itself"
    ):
        return Decision(
            "off", None, "Phase 2 (decider): a leader1 on R_I or L_V → off", "A2.decider.leader1-off"
        )
    partner = column_neighbour_with(view, {"decider"})
    found = ev.test("the other decider r′ on L_V", partner is not None, "my partner is on my vertical line")
    if found and partner is not None:
        decided = _decider_and_partner(view, r_i, k2_of(partner), ev)
        if decided is not None:
            return decided
    if ev.test("the other decider on R_I", "decider" in lights_of(r_i), "my partner moved right already"):
        return Decision(
            "decider",
            Direction.RIGHT,
            "Phase 2 (decider): the other decider is on R_I → move right",
            "A2.decider.follow",
        )
    l_i = left_neighbour_line(view, ev)
    if (
        ev.test("a call robot on L_V", "call" in lights_of(column), "a robot of my line answered")
        and ev.test("no decider on L_I", "decider" not in lights_of(l_i), "I am the left decider")
        and ev.test("all of R_I call", all(s.light == "call" for s in r_i), "R_I has answered")
    ):
        return Decision(
            "decider",
            Direction.RIGHT,
            "Phase 2 (decider): call on L_V, no decider on L_I, all of R_I call → move right",
            "A2.decider.call-right",
        )
    return stay(
        view, "Phase 2 (decider): waiting (a robot on K ∩ R_I, or the other decider)", "A2.decider.wait"
    )


def _lone_decider(view: Snapshot, ev: Evidence = NO_EVIDENCE) -> bool:
    """L2's other half: a decider made from a leader1 whose partner turned off instead sees no decider
    anywhere, nothing to its left, and only off robots on its own line (a partner still symmetric is on
    its way to becoming a decider; deciders hidden from each other by call robots, B12, see those)."""
    return (
        left_open_half_empty(view, ev)
        and ev.test("no decider in sight", "decider" not in lights_of(view.robots), "no partner anywhere")
        and ev.test("L_V all off", lights_of(vertical_line(view, ev)) <= {"off"}, "my line shows only off")
    )


def phase2_off(view: Snapshot, res: Resolutions, ev: Evidence = NO_EVIDENCE) -> Decision:
    """Algorithm 2, r.light = off, with two deciders on L_I(r) (lines 23–35)."""
    a, b = (s for s in left_neighbour_line(view, ev) if s.light == "decider")
    ev.test("two deciders on L_I", True, "Phase 2 has begun to my left")
    k2 = k2_of(a, b)
    mark_K(ev, k2)
    r_i = right_neighbour_line(view, ev)
    symmetric = is_symmetric_wrt_K(r_i, k2, ev)
    if ev.test("r on K", k2 == 0, "I am on K, the midline of the two deciders"):
        if KD in res and not symmetric:
            up = dominant_side_is_up(r_i, k2)
            if deviation(ev, KD, any((s.dy > 0) == up for s in vertical_line(view, ev))):
                return stay(
                    view,
                    "Phase 2 (off): on K, but a robot of L_V is on the dominant side → defer (KD)",
                    "A2.off.KD-defer",
                )
        return Decision(
            "leader1", None, "Phase 2 (off): two deciders on L_I and I am on K → leader1", "A2.off.on-K"
        )
    if symmetric:
        if closest_to_K(view, k2, ev) or ev.test(
            "a call robot on L_V", "call" in lights_of(vertical_line(view, ev)), "my line answered already"
        ):
            return Decision(
                "call",
                None,
                "Phase 2 (off): R_I symmetric, I am closest to K (or see call) → call",
                "A2.off.call",
            )
        return stay(view, "Phase 2 (off): R_I symmetric, not closest to K → wait", "A2.off.symmetric-wait")
    if is_terminal(view, ev) and in_dominant_half(view, k2, ev):
        return Decision(
            "leader1",
            None,
            "Phase 2 (off): R_I asymmetric, terminal in the dominant half → leader1",
            "A2.off.dominant",
        )
    return stay(view, "Phase 2 (off): R_I asymmetric, not the dominant terminal → wait", "A2.off.wait")


def phase2_call(view: Snapshot, res: Resolutions, ev: Evidence = NO_EVIDENCE) -> Decision:
    """Algorithm 2, r.light = call (lines 36–38)."""
    if G3 in res:
        seen = lights_of(view.robots)
        if deviation(ev, G3, bool(seen & {"leader1", "leader"})):
            return Decision(
                "off", None, "Phase 2 (call): a leader1/leader is visible → off (G3)", "A2.call.G3-off"
            )
    elif ev.test(
        "a leader1 on R_I or L_I",
        "leader1" in lights_of(right_neighbour_line(view, ev)) | lights_of(left_neighbour_line(view, ev)),
        "a robot next to me elected itself",
    ):
        return Decision("off", None, "Phase 2 (call): a leader1 on R_I or L_I → off", "A2.call.off")
    return stay(view, "Phase 2 (call): waiting for a leader1", "A2.call.wait")


def two_leader1_become_deciders(view: Snapshot, ev: Evidence = NO_EVIDENCE) -> Decision | None:
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
    deviation(ev, L2, True)
    left_open_half_empty(view, ev)
    extreme = not (upper_closed_half_has_other(view, ev) and bottom_closed_half_has_other(view, ev))
    r_i = right_neighbour_line(view, ev)
    k2 = k2_of(partner)
    if not extreme and robot_on_K(r_i, k2, ev) is None and is_symmetric_wrt_K(r_i, k2, ev):
        return Decision(
            "symmetric",
            None,
            "leader1 (L2): another leader1 on L_V, R_I symmetric → symmetric",
            "A2.leader1.L2-symmetric",
        )
    return Decision(
        "decider", None, "leader1 (L2): another leader1 on L_V → decider", "A2.leader1.L2-decider"
    )


def phase2_leader1(view: Snapshot, res: Resolutions, ev: Evidence = NO_EVIDENCE) -> Decision:
    """Algorithm 2, r.light = leader1 (lines 39–58)."""
    if L2 in res:
        if deviation(ev, L2, column_neighbour_with(view, {"terminal1", "symmetric"}) is not None):
            # It may be promoted on a view older than my light (B3): moving now could make the
            # configuration symmetric; it turns off on seeing me (G2), or we settle as two leader1.
            return stay(
                view,
                "leader1 (L2): a terminal1/symmetric robot on L_V → wait for it to settle",
                "A2.leader1.L2-wait",
            )
        settled = two_leader1_become_deciders(view, ev)
        if settled is not None:
            return settled
    l_i = left_neighbour_line(view, ev)
    r_i = right_neighbour_line(view, ev)
    left_all_off = all(s.light == "off" for s in l_i)
    if left_all_off and NV in res and deviation(ev, NV, not l_i):
        left_all_off = False  # the paper's "all of L_I off" holds vacuously for an empty L_I
    ev.test("all of L_I off", left_all_off, "every robot on the line to my left shows off")
    may_act = left_all_off or (
        left_open_half_empty(view, ev)
        and ev.test("all of R_I off", all(s.light == "off" for s in r_i), "every robot of R_I shows off")
    )
    if may_act:
        return _leader1_acts(view, r_i, res, ev)
    if ev.test("a leader1 on L_I", "leader1" in lights_of(l_i), "another robot to my left elected itself"):
        return Decision("off", None, "Phase 2 (leader1): another leader1 on L_I → off", "A2.leader1.off")
    return stay(view, "Phase 2 (leader1): waiting for L_I (or R_I) to turn off", "A2.leader1.wait")


def _on_an_extreme_row(view: Snapshot, ev: Evidence) -> Decision:
    """Algorithm 2, a leader1 on an extreme row: it walks left until H_L^C is empty, then leads."""
    if left_closed_half_has_other(view, ev):
        left = Decision(
            "leader1",
            Direction.LEFT,
            "Phase 2 (leader1): an extreme row, H_L^C not empty → move left",
            "A2.leader1.extreme-left",
            stride=FOREVER,
        )
        return left_walk_stride(left, view)
    return Decision(
        "leader",
        None,
        "Phase 2 (leader1): H_L^C empty and an extreme row → leader",
        "A2.leader1.leader",
    )


def _leader1_acts(view: Snapshot, r_i: list[Seen], res: Resolutions, ev: Evidence) -> Decision:
    """Algorithm 2 lines 41–53: a leader1 that may act walks to an extreme row, then left, and becomes the
    leader. Its walks promise a stride (``strides.py``)."""
    upper, bottom = upper_closed_half_has_other(view, ev), bottom_closed_half_has_other(view, ev)
    if not upper or not bottom:
        return _on_an_extreme_row(view, ev)
    if not is_terminal(view, ev):
        return Decision(
            "leader1",
            Direction.LEFT,
            "Phase 2 (leader1): not terminal on L_V → move left",
            "A2.leader1.inner-left",
        )
    if G5 in res and deviation(ev, G5, bool(r_i) and r_i[0].dx == 1 and left_open_half_empty(view, ev)):
        # B2's hidden window: the column next to me may be one I just crossed, hidden from its terminal
        # robots, which can fire Phase 1 on a stale view and step left into my column (B3 likewise): a
        # vertical walk there could meet them. Two columns away they land beside it, never on it.
        return Decision(
            "leader1",
            Direction.LEFT,
            "Phase 2 (leader1): terminal and leftmost, R_I next to me → one column further left (G5)",
            "A2.leader1.G5-left",
        )
    if not is_singleton(view, ev):
        (neighbour,) = vertical_line(view)
        away = Decision(
            "leader1",
            away_from(neighbour.dy),
            "Phase 2 (leader1): terminal, not alone on L_V → move away from r′",
            "A2.leader1.away",
            stride=FOREVER,
        )
        return vertical_stride(away, view)
    if SD in res and deviation(
        ev, SD, bool(r_i) and (all(s.dy > 0 for s in r_i) or all(s.dy < 0 for s in r_i))
    ):
        sd_away = Decision(
            "leader1",
            away_from(r_i[0].dy),
            "Phase 2 (leader1): alone on L_V → move away from R_I (SD)",
            "A2.leader1.SD-away",
            stride=FOREVER,
        )
        return vertical_stride(sd_away, view)
    up = Decision(
        "leader1",
        Direction.UP,
        "Phase 2 (leader1): alone on L_V → move along my +y",
        "A2.leader1.up",
        stride=FOREVER,
    )
    return vertical_stride(up, view)


def _decider_and_partner(view: Snapshot, r_i: list[Seen], k2: int, ev: Evidence) -> Decision | None:
    """Algorithm 2, a decider whose partner r′ is on L_V (``k2``: twice K's row): with K ∩ R_I empty,
    R_I symmetric about K waits for every robot of R_I to call, then moves right; R_I asymmetric, the
    dominant half's decider elects itself. None: a robot stands on K ∩ R_I."""
    if robot_on_K(r_i, k2, ev) is not None:
        return None
    if is_symmetric_wrt_K(r_i, k2, ev):
        if ev.test("all of R_I call", all(s.light == "call" for s in r_i), "R_I has answered"):
            return Decision(
                "decider",
                Direction.RIGHT,
                "Phase 2 (decider): R_I symmetric and all call → move right",
                "A2.decider.all-call",
            )
        return stay(
            view,
            "Phase 2 (decider): R_I symmetric → wait until all of R_I is call",
            "A2.decider.wait-call",
        )
    if in_dominant_half(view, k2, ev):
        return Decision(
            "leader1",
            None,
            "Phase 2 (decider): R_I asymmetric, I am in the dominant half → leader1",
            "A2.decider.dominant",
        )
    return stay(
        view,
        "Phase 2 (decider): R_I asymmetric, the other decider is dominant → wait",
        "A2.decider.not-dominant",
    )
