"""Every rule the paper's algorithm can fire, by stable id: the id a :class:`Decision` carries, traces
record and tests assert (the prose beside it may be reworded; the id may not).

``A1``/``A2``/``A3`` are the paper's Algorithms 1–3, then the robot's light, then the branch. A Phase-3
decision that moves a robot along a path joins two ids with ``/``: the Algorithm-3 branch, then the step
of LineMove or TargetMove (``A3.off.grow-line/LineMove.along``). A branch that exists only because of a
resolution names it (``A2.off.KD-defer``). docs/ALGORITHM.md maps each id to the paper's line.
"""

from __future__ import annotations

RULE_IDS: dict[str, str] = {
    "done": "done: stay",
    # Algorithm 1
    "A1.off.terminal": "off, terminal, H_L^O empty, no leader1 on R_I → terminal1, move left (lines 3–5)",
    "A1.off.on-K": "off, exactly two terminal1 on L_I, r on K → leader1 (lines 6–7)",
    "A1.off.wait": "off, no Phase-1 rule applies → wait",
    "A1.off.G1-wait": "off, a later light is visible → wait (G1)",
    "A1.terminal1.symmetric": "terminal1, K ∩ R_I empty, R_I symmetric → symmetric (lines 11–12)",
    "A1.terminal1.dominant": "terminal1, R_I asymmetric, r in the dominant half → leader1 (lines 14–15)",
    "A1.terminal1.not-dominant": "terminal1, R_I asymmetric, r not dominant → wait",
    "A1.terminal1.K-is-leader1": "terminal1, the robot on K ∩ R_I is leader1 → off (lines 16–17)",
    "A1.terminal1.K-wait": "terminal1, a robot on K ∩ R_I not yet leader1 → wait",
    "A1.terminal1.column-symmetric": "terminal1, a symmetric robot on L_V → symmetric (lines 18–19)",
    "A1.terminal1.column-off": "terminal1, a leader1 or off robot on L_V → off (lines 20–21)",
    "A1.terminal1.alone": "terminal1, alone on L_V, all of R_I off → leader1 (lines 22–23)",
    "A1.terminal1.wait": "terminal1, waiting for the other terminal1",
    "A1.terminal1.G2-off": "terminal1, a leader1/leader is visible → off (G2)",
    "A1.symmetric.wait": "symmetric, no symmetric/decider partner on L_V → wait",
    "A1.symmetric.move-away": "symmetric, others in H_U^C and H_B^C → move away from r′ (lines 26–27)",
    "A1.symmetric.decider": "symmetric, H_U^C or H_B^C empty → decider (lines 28–29)",
    "A1.symmetric.G2-off": "symmetric, a leader1/leader is visible → off (G2)",
    # Algorithm 2
    "A2.decider.leader1-off": "decider, a leader1 on R_I or L_V → off (lines 3–4)",
    "A2.decider.all-call": "decider, R_I symmetric and all call → move right (lines 8–9)",
    "A2.decider.wait-call": "decider, R_I symmetric, not all call → wait",
    "A2.decider.dominant": "decider, R_I asymmetric, r in the dominant half → leader1 (lines 11–12)",
    "A2.decider.not-dominant": "decider, R_I asymmetric, the other decider dominant → wait",
    "A2.decider.follow": "decider, the other decider on R_I → move right (lines 13–14)",
    "A2.decider.call-right": "decider, call on L_V, no decider on L_I, R_I all call → right (lines 16–17)",
    "A2.decider.wait": "decider, waiting",
    "A2.decider.G3-off": "decider, a leader1/leader is visible → off (G3)",
    "A2.decider.L2-alone": "decider, no other decider, nothing to the left → leader1 again (L2)",
    "A2.off.on-K": "off, two deciders on L_I, r on K → leader1 (lines 20–21)",
    "A2.off.KD-defer": "off, on K, a robot of L_V on the dominant side → wait (KD)",
    "A2.off.call": "off, R_I symmetric, closest to K or a call on L_V → call (lines 24–25)",
    "A2.off.symmetric-wait": "off, R_I symmetric, not closest to K → wait",
    "A2.off.dominant": "off, R_I asymmetric, terminal in the dominant half → leader1 (lines 27–28)",
    "A2.off.wait": "off, R_I asymmetric, not the dominant terminal → wait",
    "A2.call.off": "call, a leader1 on R_I or L_I → off (lines 30–31)",
    "A2.call.G3-off": "call, a leader1/leader is visible → off (G3)",
    "A2.call.wait": "call, waiting for a leader1",
    "A2.leader1.extreme-left": "leader1, an extreme row, H_L^C not empty → move left (lines 35–36)",
    "A2.leader1.leader": "leader1, an extreme row, H_L^C empty → leader (lines 37–38)",
    "A2.leader1.inner-left": "leader1, not terminal → move left (lines 40–41)",
    "A2.leader1.away": "leader1, terminal, not alone on L_V → move away from r′ (lines 42–43)",
    "A2.leader1.up": "leader1, alone on L_V → move along its +y (lines 44–45)",
    "A2.leader1.SD-away": "leader1, alone on L_V, R_I on one side → move away from R_I (SD)",
    "A2.leader1.G5-left": "leader1, terminal and leftmost, R_I the next column → one more column left (G5)",
    "A2.leader1.off": "leader1, another leader1 on L_I → off (lines 46–47)",
    "A2.leader1.wait": "leader1, waiting for L_I (or R_I) to turn off",
    "A2.leader1.G3-off": "leader1, a leader is visible → off (G3)",
    "A2.leader1.LW-off": "leader1, a leader1/leader to the left → off (LW)",
    "A2.leader1.L2-wait": "leader1, a terminal1/symmetric robot on L_V → wait (L2)",
    "A2.leader1.L2-symmetric": "leader1, another leader1 on L_V, R_I symmetric → symmetric (L2)",
    "A2.leader1.L2-decider": "leader1, another leader1 on L_V → decider (L2)",
    # Algorithm 3
    "A3.off.no-leader": "off in Phase 3, the leader out of sight → wait",
    "A3.off.G4-wait": "off in Phase 3, a leader1 in sight → wait (G4)",
    "A3.off.first-target": "off, line empty, a done robot seen (N2: or n = 2) → TargetMove(n−2) (lines 9–10)",
    "A3.off.start-line": "off, line empty, no done robot → LineMove(1) (lines 11–12)",
    "A3.off.grow-line": "off, line (1..i, −1) → LineMove(i+1) (lines 13–14)",
    "A3.off.next-target": "off, line (n−i..n−1, −1) → TargetMove(n−i−2) (lines 18–19)",
    "A3.off.line-unexpected": "off, the line is neither growing nor shrinking as expected → wait",
    "A3.off.not-my-turn": "off, not the leftmost of the lowest row above the line → wait",
    "A3.off.leave-line": "off, on the line, nobody above still forming → move to (x, 0) (lines 21–22)",
    "A3.off.line-wait": "off, on the line, robots above still forming → wait",
    "A3.leader.wait": "leader, robots still forming → wait (line 24)",
    "A3.leader.alone": "leader, n = 1 → done",
    "A3.leader.no-done": "leader, no done robot in sight → wait",
    "A3.leader.last-target": "leader, all others done → TargetMove(n−1) (lines 27–28; LA)",
    # LineMove and TargetMove
    "LineMove.down": "LineMove(j): above L_H1 → move down",
    "LineMove.along": "LineMove(j): on L_H1 → move horizontally towards (j, 0)",
    "LineMove.into-line": "LineMove(j): at (j, 0) → move to (j, −1)",
    "TargetMove.vertical": "TargetMove(j): move vertically towards L_(t_j−1)",
    "TargetMove.along": "TargetMove(j): on L_(t_j−1) → move horizontally",
    "TargetMove.into": "TargetMove(j): below t_j → move up into it",
    "TargetMove.done": "TargetMove(j): at t_j → done",
    "TargetMove.missing": "t_j does not exist (a view inconsistent with the pattern's size) → wait",
}


def parts(rule_id: str) -> list[str]:
    """The registry ids a decision's id is made of (``A3.off.grow-line/LineMove.along`` is two)."""
    return rule_id.split("/")
