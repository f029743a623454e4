"""Write apf_viz/algorithms/apf_opaque_grid/pseudocode.json from the transcription below: the paper's
three algorithms as its LaTeX writes them (``../shared/paper/apf_opaque_grid.tex``), one line per numbered
line, ". " per level of indentation; the numbers are checked to run on without a gap.

Run: python scripts/make_pseudocode.py apf_viz/algorithms/apf_opaque_grid/pseudocode.json
"""

# ruff: noqa: E501

import argparse
import json
import re
import sys

from apf_viz.core.files import write_atomic
from apf_viz.core.formats import InputError

A1 = """
Procedure Phase1()
 1 r ← myself
 2 if r.light = off then
 3 .  if r is terminal and there is no robot in H_L^O(r) and no robot leader1 in R_I(r) then
 4 .  .  r.light ← terminal1
 5 .  .  move left
 6 .  else if there are exactly two robots in L_I(r) having light terminal1 and r is on K then
 7 .  .  r.light ← leader1
 8 else if r.light = terminal1 then
 9 .  if there is a robot with light terminal1 on L_V(r) then
10 .  .  if no robots on K ∩ R_I(r) then
11 .  .  .  if R_I(r) is symmetric with respect to K then
12 .  .  .  .  r.light ← symmetric
13 .  .  .  else
14 .  .  .  .  if r is in dominant half then
15 .  .  .  .  .  r.light ← leader1
16 .  .  else if there is a robot on K ∩ R_I(r) with light leader1 then
17 .  .  .  r.light ← off
18 .  else if there is a robot with light symmetric on L_V(r) then
19 .  .  r.light ← symmetric
20 .  else if there is a robot with light leader1 or off on L_V(r) then
21 .  .  r.light ← off
22 .  else if r is singleton on L_V(r) and all robots in R_I(r) are off then
23 .  .  r.light ← leader1
24 else if r.light = symmetric then
25 .  if there is a robot r′ with light symmetric or decider on L_V(r) then
26 .  .  if there is other robot both in H_U^C(r) and H_B^C(r) then
27 .  .  .  move vertically opposite to r′
28 .  .  else
29 .  .  .  r.light ← decider
"""
A2 = """
Procedure Phase2()
 1 r ← myself
 2 if r.light = decider then
 3 .  if there is a robot with light leader1 on R_I(r) or L_V(r) then
 4 .  .  r.light ← off
 5 .  else
 6 .  .  if there is a robot with light decider on L_V(r) and no robots on K ∩ R_I(r) then
 7 .  .  .  if R_I(r) is symmetric with respect to K then
 8 .  .  .  .  if all robots in R_I(r) are call then
 9 .  .  .  .  .  move right
10 .  .  .  else
11 .  .  .  .  if r is in dominant half then
12 .  .  .  .  .  r.light ← leader1
13 .  .  else if there is a robot with light decider in R_I(r) then
14 .  .  .  move right
15 .  .  else if there is a robot with light call in L_V(r) and no robot with light decider in L_I(r) then
16 .  .  .  if all robots in R_I(r) are call then
17 .  .  .  .  move right
18 else if r.light = off then
19 .  if there are two robots with light decider in L_I(r) then
20 .  .  if r is on K ∩ L_V(r) then
21 .  .  .  r.light ← leader1
22 .  .  else
23 .  .  .  if R_I(r) is symmetric with respect to K then
24 .  .  .  .  if r is closest to K or there is a robot with light call on L_V(r) then
25 .  .  .  .  .  r.light ← call
26 .  .  .  else
27 .  .  .  .  if r is terminal on L_V(r) and in dominant half then
28 .  .  .  .  .  r.light ← leader1
29 else if r.light = call then
30 .  if there is a robot with light leader1 in R_I(r) or L_I(r) then
31 .  .  r.light ← off
32 else if r.light = leader1 then
33 .  if (all robots in L_I(r) are off) or (H_L^O(r) is empty and all robots in R_I(r) are off) then
34 .  .  if there is no other robot in H_U^C(r) or H_B^C(r) then
35 .  .  .  if there is other robot in H_L^C(r) then
36 .  .  .  .  move left
37 .  .  .  else
38 .  .  .  .  r.light ← leader
39 .  .  else
40 .  .  .  if r is not terminal on L_V(r) then
41 .  .  .  .  move left
42 .  .  .  else if r is terminal on L_V(r) and there is another robot r′ on L_V(r) then
43 .  .  .  .  move vertically opposite to r′
44 .  .  .  else if r is singleton on L_V(r) then
45 .  .  .  .  move vertically according to its positive y-axis
46 .  else if there is a robot with light leader1 in L_I(r) then
47 .  .  r.light ← off
"""
A3 = """
Procedure PatternFormationFromLeaderConfiguration()
 1 r ← myself
 2 r₀ ← the robot with light leader
 3 if r.light = off then
 4 .  if (r₀ ∈ H_B^O(r)) and (r is leftmost on L_H(r)) and (there is no robot in H_B^O(r) ∩ H_U^O(r₀)) then
 5 .  .  if there are no robots on L_H(r₀) other than r₀ then
 6 .  .  .  if there is a robot with light done then
 7 .  .  .  .  if r is at t_{n−2} then
 8 .  .  .  .  .  r.light ← done
 9 .  .  .  .  else
10 .  .  .  .  .  TargetMove(n−2)
11 .  .  .  else
12 .  .  .  .  LineMove(1)
13 .  .  else if there are i robots on L_H(r₀) other than r₀ at (1, −1), …, (i, −1) then
14 .  .  .  LineMove(i+1)
15 .  .  else if there are i robots on L_H(r₀) other than r₀ at (n−i, −1), …, (n−1, −1) then
16 .  .  .  if r is at t_{n−i−2} then
17 .  .  .  .  r.light ← done
18 .  .  .  else
19 .  .  .  .  TargetMove(n−i−2)
20 .  else if r₀ ∈ L_H(r) and H_U^O(r) has no robots with light off then
21 .  .  if r is at (i, −1) then
22 .  .  .  move to (i, 0)
23 else if r.light = leader then
24 .  if there are no robots with light off then
25 .  .  if r is at t_{n−1} then
26 .  .  .  r.light ← done
27 .  .  else
28 .  .  .  TargetMove(n−1)
Procedure LineMove(j)
29 if r is on L_H1 then
30 .  if r is at (j, 0) then
31 .  .  move to (j, −1)
32 .  else
33 .  .  move horizontally towards (j, 0)
34 else
35 .  move vertically towards L_H1
Procedure TargetMove(j)
36 if r is on L_{t_j−1} then
37 .  if r is at (t_j(x), t_j(y)−1) then
38 .  .  move to (t_j(x), t_j(y))
39 .  else
40 .  .  move horizontally towards (t_j(x), t_j(y)−1)
41 else
42 .  move vertically towards L_{t_j−1}
"""


def parse(text):
    procs, n_expected = [], 1
    for raw in text.strip("\n").splitlines():
        if raw.startswith("Procedure "):
            procs.append({"title": raw, "lines": []})
            continue
        m = re.match(r"\s*(\d+) ((?:\.  )*)(.*)$", raw)
        assert m, raw
        n = int(m.group(1))
        assert n == n_expected, (n, raw)
        n_expected += 1
        procs[-1]["lines"].append({"n": n, "depth": len(m.group(2)) // 3, "text": m.group(3)})
    return procs


ALGORITHMS = [
    {"id": "A1", "title": "Algorithm 1: Phase 1 (leader election)", "procedures": parse(A1)},
    {"id": "A2", "title": "Algorithm 2: Phase 2 (leader selection)", "procedures": parse(A2)},
    {
        "id": "A3",
        "title": "Algorithm 3: Pattern formation from leader configuration",
        "procedures": parse(A3),
    },
]

# Where each resolution changes the paper: a line inserted after line `after` (at `depth`), or a line
# that `replaces` one of the paper's. Shown in another colour, named; gone with the literal paper.
RESOLUTION_LINES = [
    {
        "algorithm": "A1",
        "after": 2,
        "depth": 1,
        "resolution": "G1",
        "text": "if r sees a light other than off or terminal1 then wait",
    },
    {
        "algorithm": "A1",
        "replaces": 6,
        "depth": 1,
        "resolution": "E2",
        "text": "else if L_I(r) holds exactly two robots, both with light terminal1, and r is on K then",
    },
    {
        "algorithm": "A1",
        "after": 8,
        "depth": 1,
        "resolution": "G2",
        "text": "if r sees a robot with light leader1 or leader then r.light ← off",
    },
    {
        "algorithm": "A1",
        "after": 24,
        "depth": 1,
        "resolution": "G2",
        "text": "if r sees a robot with light leader1 or leader then r.light ← off",
    },
    {
        "algorithm": "A2",
        "after": 2,
        "depth": 1,
        "resolution": "G3",
        "text": "if r sees a robot with light leader1 or leader, wherever it is, then r.light ← off",
    },
    {
        "algorithm": "A2",
        "after": 2,
        "depth": 1,
        "resolution": "L2",
        "text": "if no other decider is in sight and H_L^O(r) is empty then r.light ← leader1",
    },
    {
        "algorithm": "A2",
        "replaces": 20,
        "depth": 2,
        "resolution": "KD",
        "text": "if r is on K ∩ L_V(r), unless R_I(r) is asymmetric and a robot of L_V(r) stands in the dominant half, then",
    },
    {
        "algorithm": "A2",
        "after": 29,
        "depth": 1,
        "resolution": "G3",
        "text": "if r sees a robot with light leader1 or leader, wherever it is, then r.light ← off",
    },
    {
        "algorithm": "A2",
        "after": 32,
        "depth": 1,
        "resolution": "G3",
        "text": "if r sees a robot with light leader then r.light ← off",
    },
    {
        "algorithm": "A2",
        "after": 32,
        "depth": 1,
        "resolution": "LW",
        "text": "if r sees a robot with light leader1 or leader to its left then r.light ← off",
    },
    {
        "algorithm": "A2",
        "after": 32,
        "depth": 1,
        "resolution": "L2",
        "text": "if a robot with light terminal1 or symmetric is on L_V(r) then wait",
    },
    {
        "algorithm": "A2",
        "after": 32,
        "depth": 1,
        "resolution": "L2",
        "text": "if another leader1 is on L_V(r) then r.light ← symmetric if R_I(r) is symmetric, else decider",
    },
    {
        "algorithm": "A2",
        "replaces": 33,
        "depth": 1,
        "resolution": "NV",
        "text": "if (L_I(r) is not empty and all robots in L_I(r) are off) or (H_L^O(r) is empty and all robots in R_I(r) are off) then",
    },
    {
        "algorithm": "A2",
        "after": 41,
        "depth": 3,
        "resolution": "G5",
        "text": "else if H_L^O(r) is empty and R_I(r) is the next vertical line then move left",
    },
    {
        "algorithm": "A2",
        "replaces": 45,
        "depth": 4,
        "resolution": "SD",
        "text": "move vertically away from R_I(r) if R_I(r) lies on one side of L_H(r), else along its positive y-axis",
    },
    {
        "algorithm": "A3",
        "after": 3,
        "depth": 1,
        "resolution": "G4",
        "text": "if r sees a robot with light leader1 then wait",
    },
    {
        "algorithm": "A3",
        "replaces": 6,
        "depth": 3,
        "resolution": "N2",
        "text": "if there is a robot with light done, or n = 2, then",
    },
    {
        "algorithm": "A3",
        "replaces": 20,
        "depth": 1,
        "resolution": "P3",
        "text": "else if r₀ ∈ L_H(r) and H_U^O(r) has no robot that is not done then",
    },
    {
        "algorithm": "A3",
        "replaces": 24,
        "depth": 1,
        "resolution": "P3",
        "text": "if every other robot is done then",
    },
    {
        "algorithm": "A3",
        "replaces": 28,
        "depth": 3,
        "resolution": "LA",
        "text": "TargetMove(n−1) in the frame the done robots fix (t_{n−2} anchors it), not its own",
    },
]

# Each rule id: the line(s) whose action it is (or the condition it stops at), by algorithm and number;
# a resolution's rule names its line by the resolution ("G2@A1.8": the G2 line after line 8 of A1).
RULES = {
    "A1.off.terminal": ["A1.4", "A1.5"],
    "A1.off.on-K": ["A1.7"],
    "A1.off.wait": ["A1.2"],
    "A1.off.G1-wait": ["G1@A1.2"],
    "A1.terminal1.symmetric": ["A1.12"],
    "A1.terminal1.dominant": ["A1.15"],
    "A1.terminal1.not-dominant": ["A1.14"],
    "A1.terminal1.K-is-leader1": ["A1.17"],
    "A1.terminal1.K-wait": ["A1.16"],
    "A1.terminal1.column-symmetric": ["A1.19"],
    "A1.terminal1.column-off": ["A1.21"],
    "A1.terminal1.alone": ["A1.23"],
    "A1.terminal1.wait": ["A1.8"],
    "A1.terminal1.G2-off": ["G2@A1.8"],
    "A1.symmetric.wait": ["A1.25"],
    "A1.symmetric.move-away": ["A1.27"],
    "A1.symmetric.decider": ["A1.29"],
    "A1.symmetric.G2-off": ["G2@A1.24"],
    "A2.decider.leader1-off": ["A2.4"],
    "A2.decider.all-call": ["A2.9"],
    "A2.decider.wait-call": ["A2.8"],
    "A2.decider.dominant": ["A2.12"],
    "A2.decider.not-dominant": ["A2.11"],
    "A2.decider.follow": ["A2.14"],
    "A2.decider.call-right": ["A2.17"],
    "A2.decider.wait": ["A2.2"],
    "A2.decider.G3-off": ["G3@A2.2"],
    "A2.decider.L2-alone": ["L2@A2.2"],
    "A2.off.on-K": ["A2.21"],
    "A2.off.KD-defer": ["KD@A2.20"],
    "A2.off.call": ["A2.25"],
    "A2.off.symmetric-wait": ["A2.24"],
    "A2.off.dominant": ["A2.28"],
    "A2.off.wait": ["A2.27"],
    "A2.call.off": ["A2.31"],
    "A2.call.G3-off": ["G3@A2.29"],
    "A2.call.wait": ["A2.30"],
    "A2.leader1.extreme-left": ["A2.36"],
    "A2.leader1.leader": ["A2.38"],
    "A2.leader1.inner-left": ["A2.41"],
    "A2.leader1.away": ["A2.43"],
    "A2.leader1.up": ["A2.45"],
    "A2.leader1.SD-away": ["SD@A2.45"],
    "A2.leader1.G5-left": ["G5@A2.41"],
    "A2.leader1.off": ["A2.47"],
    "A2.leader1.wait": ["A2.33"],
    "A2.leader1.G3-off": ["G3@A2.32"],
    "A2.leader1.LW-off": ["LW@A2.32"],
    "A2.leader1.L2-wait": ["L2@A2.32"],
    "A2.leader1.L2-symmetric": ["L2@A2.32:2"],
    "A2.leader1.L2-decider": ["L2@A2.32:2"],
    "A3.off.no-leader": ["A3.2"],
    "A3.off.G4-wait": ["G4@A3.3"],
    "A3.off.first-target": ["A3.10"],
    "A3.off.start-line": ["A3.12"],
    "A3.off.grow-line": ["A3.14"],
    "A3.off.next-target": ["A3.19"],
    "A3.off.line-unexpected": ["A3.15"],
    "A3.off.not-my-turn": ["A3.4"],
    "A3.off.leave-line": ["A3.22"],
    "A3.off.line-wait": ["A3.20"],
    "A3.leader.wait": ["A3.24"],
    "A3.leader.alone": ["A3.26"],
    "A3.leader.no-done": ["A3.24"],
    "A3.leader.last-target": ["A3.28"],
    "LineMove.down": ["A3.35"],
    "LineMove.along": ["A3.33"],
    "LineMove.into-line": ["A3.31"],
    "TargetMove.vertical": ["A3.42"],
    "TargetMove.along": ["A3.40"],
    "TargetMove.into": ["A3.38"],
    "TargetMove.done": ["A3.8", "A3.17", "A3.26"],
}
# Composite ids whose parts' lines are narrowed by their context (the caller's "if r is at t_j").
CONTEXT = {
    "A3.off.first-target/TargetMove.done": ["A3.8"],
    "A3.off.next-target/TargetMove.done": ["A3.17"],
    "A3.leader.last-target/TargetMove.done": ["A3.26"],
}
# Rule ids the pseudocode has no line for, each with the reason.
OUTSIDE = {
    "done": "a robot with light done has reached its target and never acts again (Section 3.2, in prose)",
    "TargetMove.missing": "t_j does not exist: a view inconsistent with the pattern's size, which the paper "
    "assumes cannot happen; the robot waits",
}
# The paper's lines no rule can reach, each with the reason (declarations, and `else` lines whose
# branch is another line's).

# The paper's numbered lines no rule's line or enclosing condition is, each with the reason.
UNREACHED = {
    "A1.1": "a declaration every branch of Algorithm 1 reads, not a branch",
    "A2.1": "a declaration every branch of Algorithm 2 reads, not a branch",
    "A3.1": "a declaration every branch of Algorithm 3 reads, not a branch",
}

out = {
    "algorithms": ALGORITHMS,
    "resolution_lines": RESOLUTION_LINES,
    "rules": RULES,
    "context": CONTEXT,
    "outside": OUTSIDE,
    "unreached": UNREACHED,
}
parser = argparse.ArgumentParser(description="Write the paper's pseudocode, transcribed, as JSON.")
parser.add_argument("out", help="apf_viz/algorithms/apf_opaque_grid/pseudocode.json")
target = parser.parse_args().out
try:
    write_atomic(target, json.dumps(out, ensure_ascii=False, indent=1))  # a reader never sees half a file
except InputError as e:  # not a regular file: nothing written
    sys.exit(f"make_pseudocode: {e}")
print(f"wrote {target}")
