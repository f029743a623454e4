"""The named resolutions of the paper's gaps (see docs/ALGORITHM.md and the implementers' notes).

Each can be switched on or off by name. ``apf-opaque-grid`` enables all of them; the literal variant
enables only what the paper needs to run at all.
"""

from __future__ import annotations

RESOLUTIONS: dict[str, str] = {
    "G1": "an off robot that sees any light other than off/terminal1 does not run Phase 1 again (B1)",
    "G2": "terminal1/symmetric robots that see a leader1/leader turn off (hidden window, B2/B3)",
    "G3": "decider/call robots turn off on seeing any leader1/leader, wherever it is (B5, B10)",
    "NV": "'all robots in L_I are off' requires L_I to be non-empty (B6)",
    "KD": "the K robot defers to the dominant terminal robot of its line when R_I is asymmetric (B7)",
    "LW": "a leader1 that sees a leader1/leader to its left turns off (B8)",
    "E2": "off rule (b) needs L_I to hold exactly the two terminal1 robots (B4)",
    "SD": "a singleton leader1 moves away from R_I when R_I lies on one side (B3)",
    "P3": "Phase 3 waits for robots that are not done, not only for off ones (B19)",
    "LA": "the leader anchors its frame on t_{n-2}, not on itself, for its last TargetMove (B18)",
    "N2": "with n = 2 the single follower goes to its target instead of LineMove(1) again (B17)",
    "L2": "two leader1 on one leftmost line, on extreme rows, become the deciders of a stable configuration",
}

ALL = frozenset(RESOLUTIONS)
# LA is needed for any run to finish: without it the leader's frame moves with it and TargetMove(n-1)
# never ends (B18), whatever n is. Every other resolution fixes a failure that happens only sometimes.
LITERAL = frozenset({"LA"})
