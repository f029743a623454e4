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
    mark_K,
    right_neighbour_line,
    robot_on_K,
    upper_closed_half_has_other,
    vertical_line,
)
from apf_viz.algorithms.apf_opaque_grid.resolutions import E2, Resolutions, deviation
from apf_viz.core.algorithm import Decision, Watch
from apf_viz.core.grid import Direction
from apf_viz.core.portrayal import NO_EVIDENCE, Evidence
from apf_viz.core.view import Seen, Snapshot


def stay(view: Snapshot, rule: str, rule_id: str = "", watch: Watch | None = None) -> Decision:
    """Keep the light and do not move; ``watch``: what the answer depends on (None: the whole view)."""
    return Decision(view.light, None, rule, rule_id, watch)


def away_from(dy: int) -> Direction:
    """'Move vertically opposite to r′' for a column neighbour at this dy."""
    return Direction.DOWN if dy > 0 else Direction.UP


def phase1_off(view: Snapshot, res: Resolutions, ev: Evidence = NO_EVIDENCE) -> Decision:
    """Algorithm 1, r.light = off (lines 3–7)."""
    r_i = right_neighbour_line(view, ev)
    terminal = is_terminal(view, ev)
    if (
        terminal
        and left_open_half_empty(view, ev)
        and ev.test("no leader1 on R_I", "leader1" not in lights_of(r_i), "no robot of R_I shows leader1")
    ):
        return Decision(
            "terminal1",
            Direction.LEFT,
            "Phase 1 (off): terminal, H_L^O empty, no leader1 on R_I → terminal1, move left",
            "A1.off.terminal",
        )
    l_i = left_neighbour_line(view, ev)
    terminals = [s for s in l_i if s.light == "terminal1"]
    exactly_two = len(terminals) == 2
    if exactly_two and E2 in res and deviation(ev, E2, len(l_i) != 2):
        exactly_two = False  # the paper's line counts only the terminal1 robots of L_I
    ev.test("two terminal1 on L_I", exactly_two, "L_I holds exactly two terminal1 robots")
    if exactly_two:
        k2 = k2_of(terminals[0], terminals[1])
        mark_K(ev, k2)
        if ev.test("r on K", k2 == 0, "I am on K, the midline of the two terminal1 robots"):
            return Decision(
                "leader1",
                None,
                "Phase 1 (off): two terminal1 on L_I and I am on K → leader1",
                "A1.off.on-K",
            )
    return stay(view, "Phase 1 (off): no rule applies → wait", "A1.off.wait")


def phase1_terminal1(view: Snapshot, res: Resolutions, ev: Evidence = NO_EVIDENCE) -> Decision:
    """Algorithm 1, r.light = terminal1 (lines 8–24)."""
    partner = column_neighbour_with(view, {"terminal1"})
    ev.test("another terminal1 on L_V", partner is not None, "my vertical line holds the other terminal1 r′")
    r_i = right_neighbour_line(view, ev)
    if partner is not None:
        return _terminal1_pair(view, r_i, k2_of(partner), ev)
    column = lights_of(vertical_line(view, ev))
    if ev.test("a symmetric robot on L_V", "symmetric" in column, "my vertical line shows symmetric"):
        return Decision(
            "symmetric",
            None,
            "Phase 1 (terminal1): a symmetric robot on L_V → symmetric",
            "A1.terminal1.column-symmetric",
        )
    if ev.test(
        "a leader1 or off robot on L_V", bool(column & {"leader1", "off"}), "my line is not all terminal1"
    ):
        return Decision(
            "off", None, "Phase 1 (terminal1): a leader1 or off robot on L_V → off", "A1.terminal1.column-off"
        )
    if is_singleton(view, ev) and ev.test(
        "all of R_I off", all(s.light == "off" for s in r_i), "every robot of R_I shows off"
    ):
        return Decision(
            "leader1",
            None,
            "Phase 1 (terminal1): alone on L_V, all of R_I off → leader1",
            "A1.terminal1.alone",
        )
    return stay(view, "Phase 1 (terminal1): waiting for the other terminal1", "A1.terminal1.wait")


def _terminal1_pair(view: Snapshot, r_i: list[Seen], k2: int, ev: Evidence) -> Decision:
    """Algorithm 1, a terminal1 whose partner r′ is on L_V (``k2``: twice K's row): K ∩ R_I empty, R_I
    symmetric → symmetric, asymmetric → the dominant half's robot elects itself; a robot on K ∩ R_I →
    wait for it to become leader1, then off."""
    on_k = robot_on_K(r_i, k2, ev)
    if on_k is None:
        if is_symmetric_wrt_K(r_i, k2, ev):
            return Decision(
                "symmetric",
                None,
                "Phase 1 (terminal1): K ∩ R_I empty, R_I symmetric → symmetric",
                "A1.terminal1.symmetric",
            )
        if in_dominant_half(view, k2, ev):
            return Decision(
                "leader1",
                None,
                "Phase 1 (terminal1): R_I asymmetric, I am in the dominant half → leader1",
                "A1.terminal1.dominant",
            )
        return stay(
            view,
            "Phase 1 (terminal1): R_I asymmetric, I am not in the dominant half → wait",
            "A1.terminal1.not-dominant",
        )
    if ev.test("the robot on K ∩ R_I is leader1", on_k.light == "leader1", "it has elected itself"):
        return Decision(
            "off",
            None,
            "Phase 1 (terminal1): the robot on K ∩ R_I is leader1 → off",
            "A1.terminal1.K-is-leader1",
        )
    return stay(
        view,
        "Phase 1 (terminal1): a robot is on K ∩ R_I → wait for it to become leader1",
        "A1.terminal1.K-wait",
    )


def phase1_symmetric(view: Snapshot, res: Resolutions, ev: Evidence = NO_EVIDENCE) -> Decision:
    """Algorithm 1, r.light = symmetric (lines 25–31)."""
    partner = column_neighbour_with(view, {"symmetric", "decider"})
    vertical_line(view, ev)
    if (
        not ev.test(
            "a symmetric/decider robot r′ on L_V", partner is not None, "my partner on my vertical line"
        )
        or partner is None
    ):
        return stay(
            view, "Phase 1 (symmetric): no symmetric/decider robot on L_V → wait", "A1.symmetric.wait"
        )
    if upper_closed_half_has_other(view, ev) and bottom_closed_half_has_other(view, ev):
        return Decision(
            "symmetric",
            away_from(partner.dy),
            "Phase 1 (symmetric): others in H_U^C and H_B^C → move away from r′",
            "A1.symmetric.move-away",
        )
    return Decision(
        "decider", None, "Phase 1 (symmetric): H_U^C or H_B^C empty → decider", "A1.symmetric.decider"
    )
