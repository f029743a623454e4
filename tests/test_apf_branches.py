"""One test per branch of the paper's three procedures, on small hand-made starts that reach it.

Starts are global (x, y); both-terminal branches use FSYNC so that both terminals Look before either
moves (the notes' "synchronous first round"). Each test also checks that the run forms the pattern.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from apf_viz.algorithms.apf_opaque_grid import embedded_targets
from tests.apf_helpers import fired, line, run, without

STARTS = Path(__file__).parent.parent / "demo_patterns" / "starts"


def start(name: str) -> list[tuple[int, int]]:
    return [tuple(p) for p in json.loads((STARTS / f"{name}.json").read_text())["robots"]]


def test_phase1_single_robot_on_L1_becomes_leader1_then_leader():
    e, audit, rules = run(start("one-on-L1-3"))
    assert audit.ok, audit.problems
    assert fired(rules, "Phase 1 (off): terminal, H_L^O empty, no leader1 on R_I → terminal1, move left") == 1
    assert fired(rules, "Phase 1 (terminal1): alone on L_V, all of R_I off → leader1") == 1
    assert fired(rules, "Phase 2 (leader1): H_L^C empty and an extreme row → leader") == 1


def test_phase1_two_terminals_with_a_robot_on_K():
    e, audit, rules = run(start("robots-on-K-5"), algorithm=without("G2"))
    assert audit.ok, audit.problems
    assert fired(rules, "Phase 1 (off): two terminal1 on L_I and I am on K → leader1") == 1
    assert fired(rules, "Phase 1 (terminal1): the robot on K ∩ R_I is leader1 → off") == 2
    # The K robot is not terminal: it walks left along K, between the two ex-terminals (Lemma P2:l7).
    assert fired(rules, "Phase 2 (leader1): not terminal on L_V → move left") >= 1


def test_phase1_asymmetric_R_I_the_dominant_terminal_decides():
    # Terminals (after moving left) at y = 0 and 2: K at y = 1; R_I has y = 0 (distance 1) and 3 (2):
    # the lower side dominates, so the lower terminal, robot 0, becomes leader1.
    e, audit, rules = run([(0, 0), (0, 2), (1, 0), (1, 3)])
    assert audit.ok, audit.problems
    promoted = [ev.robot for ev in e.history.events() if ev.phase == "compute" and ev.light == "leader1"]
    assert set(promoted) == {0}
    assert fired(rules, "Phase 1 (terminal1): R_I asymmetric, I am in the dominant half → leader1") == 1


def test_phase1_symmetric_then_deciders_and_phase2_dominant_decider():
    # R_I symmetric about K = 1 → symmetric; the robots move apart to rows 6 and −1 (K shifts to 2.5,
    # B9), where R_I is no longer symmetric: the dominant decider becomes leader1.
    e, audit, rules = run([(0, 0), (0, 2), (1, 0), (1, 2), (2, 5)])
    assert audit.ok, audit.problems
    assert fired(rules, "Phase 1 (terminal1): K ∩ R_I empty, R_I symmetric → symmetric") == 2
    assert fired(rules, "Phase 1 (symmetric): others in H_U^C and H_B^C → move away from r′") >= 2
    assert fired(rules, "Phase 1 (symmetric): H_U^C or H_B^C empty → decider") == 2
    assert fired(rules, "Phase 2 (decider): R_I asymmetric, I am in the dominant half → leader1") == 1


def test_phase2_symmetric_R_I_leads_to_call_and_the_deciders_move_right():
    e, audit, rules = run(start("sym-call-7"))
    assert audit.ok, audit.problems
    assert fired(rules, "Phase 2 (off): R_I symmetric, I am closest to K (or see call) → call") == 2
    assert fired(rules, "Phase 2 (decider): R_I symmetric and all call → move right") >= 2
    assert fired(rules, "Phase 2 (off): two deciders on L_I and I am on K → leader1") == 1
    assert fired(rules, "Phase 2 (call): a leader1/leader is visible → off") == 2


@pytest.mark.parametrize(
    ("algorithm", "rule"),
    [
        ("apf-opaque-grid", "(L2)"),
        (without("L2"), "leader1: a leader1/leader to my left → off (LW)"),
        (without("L2", "LW"), "Phase 2 (leader1): another leader1 on L_I → off"),
    ],
)
def test_phase2_two_leader1_resolve_to_one(algorithm, rule):
    for seed in range(200):
        e, audit, rules = run(
            [(3, 2), (1, 2), (0, 2), (2, 0), (0, 3)], scheduler="async", seed=seed, algorithm=algorithm
        )
        assert audit.ok, (seed, audit.problems)
        if audit.max_leader1 == 2:
            assert fired(rules, rule) >= 1
            assert audit.max_leaders == 1
            return
    pytest.fail("no schedule in 200 seeds produced two leader1 robots")


def test_phase2_leader1_terminal_on_a_shared_line_moves_away_from_its_neighbour():
    e, audit, rules = run(start("vertical-line-4"))
    assert audit.ok, audit.problems
    assert fired(rules, "Phase 2 (leader1): terminal, not alone on L_V → move away from r′") >= 1


def test_phase3_compact_line_then_targets_in_order_and_the_leader_last():
    pattern = [(0, 0), (1, 0), (2, 0), (0, 1), (2, 1), (1, 2), (3, 2)]
    e, audit, rules = run(start("sym-call-7"), pattern=pattern, scheduler="async", seed=4)
    assert audit.ok, audit.problems
    n = len(pattern)
    # The compact line: when the left end first leaves, the leader and n−1 robots fill one row.
    first_leave = next(
        i
        for i, step in enumerate(e.history.steps)
        if any(
            (ev.rule or "").startswith("Phase 3 (off): left end of the line at (1, −1)") for ev in step.events
        )
    )
    e.seek(first_leave)
    leader = e.state.lights.index("leader")
    lx, ly = e.current_points()[leader]
    row = sorted(x - lx for x, y in e.current_points() if y == ly)
    assert row == list(range(n))
    # Targets are taken in the order t_0, t_1, …, t_{n−2}, and the leader takes t_{n−1} last.
    e.seek(e.history.length)
    done = [ev for ev in e.history.events() if ev.phase == "compute" and "→ done" in (ev.rule or "")]
    order = [int((ev.rule or "").split("TargetMove(")[1].split(")")[0]) for ev in done]
    assert order == list(range(n))
    assert e.state.lights[done[-1].robot] == "done" and done[-1].robot == leader
    assert embedded_targets(tuple(pattern))[-1] == (0, 1)


def test_phase3_two_robots_need_N2():
    e, audit, rules = run([(0, 0), (1, 0)], pattern=[(0, 0), (0, 1)], scheduler="async", max_events=20_000)
    assert audit.ok, audit.problems
    e, audit, rules = run(
        [(0, 0), (1, 0)],
        pattern=[(0, 0), (0, 1)],
        scheduler="async",
        max_events=20_000,
        algorithm=without("N2"),
    )
    assert audit.outcome == "limit"  # the paper livelocks: LineMove(1) again and again (B17)
    assert fired(rules, "LineMove(1)") > 10


def test_every_decision_names_its_rule():
    e, audit, rules = run(start("sym-call-7"), scheduler="async", seed=2)
    assert rules and all(rules)
    assert all(r.split(":")[0] for r in rules)


def test_a_single_robot_is_a_single_point_formed_at_time_0():
    e, audit, rules = run([(4, 7)], pattern=[(0, 0)], scheduler="async")
    assert audit.ok, audit.problems
    assert (audit.outcome, audit.events, audit.moves) == ("formed", 0, 0)


def test_lines_of_the_default_pattern_helper():
    assert line(3) == [(0, 0), (1, 0), (2, 0)]
