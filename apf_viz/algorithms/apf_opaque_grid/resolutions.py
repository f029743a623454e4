"""The named resolutions of the paper's gaps (see docs/ALGORITHM.md and the implementers' notes).

Each can be switched on or off by name. ``apf-opaque-grid`` enables all of them; the literal variant
enables only what the paper needs to run at all.
"""

from __future__ import annotations

from enum import StrEnum


class Resolution(StrEnum):
    """A named resolution of one of the paper's gaps: a typed flag, compared as ``R.G3 in res``."""

    G1 = "G1"
    G2 = "G2"
    G3 = "G3"
    NV = "NV"
    KD = "KD"
    LW = "LW"
    E2 = "E2"
    SD = "SD"
    P3 = "P3"
    LA = "LA"
    N2 = "N2"
    L2 = "L2"
    G4 = "G4"
    G5 = "G5"


R = Resolution
Resolutions = frozenset[Resolution]
# The flags as module constants: an Enum class's attribute access (R.G3) is slow enough in Python 3.11 to
# show in a run's time, and the rules test flags on every decision (docs/PERFORMANCE.md).
G1, G2, G3, NV, KD, LW, E2, SD, P3, LA, N2, L2, G4, G5 = Resolution

RESOLUTIONS: dict[Resolution, str] = {
    R.G1: "an off robot that sees any light other than off/terminal1 does not run Phase 1 again (B1)",
    R.G2: "terminal1/symmetric robots that see a leader1/leader turn off (hidden window, B2/B3)",
    R.G3: "decider/call robots turn off on seeing any leader1/leader, wherever it is (B5, B10)",
    R.NV: "'all robots in L_I are off' requires L_I to be non-empty (B6)",
    R.KD: "the K robot defers to the dominant terminal robot of its line when R_I is asymmetric (B7)",
    R.LW: "a leader1 that sees a leader1/leader to its left turns off (B8)",
    R.E2: "off rule (b) needs L_I to hold exactly the two terminal1 robots (B4)",
    R.SD: "a singleton leader1 moves away from R_I when R_I lies on one side (B3)",
    R.P3: "Phase 3 waits for robots that are not done, not only for off ones (B19)",
    R.LA: "the leader anchors its frame on t_{n-2}, not on itself, for its last TargetMove (B18)",
    R.N2: "with n = 2 the single follower goes to its target instead of LineMove(1) again (B17)",
    R.L2: "two leader1 on one leftmost line, on extreme rows, become the deciders of a stable configuration",
    R.G4: "an off robot in Phase 3 waits while it sees a leader1 (a second leader1 may hold a stale move)",
    R.G5: "a leftmost terminal leader1 steps left until R_I is not the next column, then walks vertically",
}

ALL: Resolutions = frozenset(Resolution)
# LA is needed for any run to finish: without it the leader's frame moves with it and TargetMove(n-1)
# never ends (B18), whatever n is. Every other resolution fixes a failure that happens only sometimes.
LITERAL: Resolutions = frozenset({R.LA})


def parse_resolutions(names: set[str] | frozenset[str]) -> Resolutions:
    """Resolution flags from their names; an unknown name is a one-line ``ValueError``."""
    unknown = sorted(set(names) - set(Resolution))
    if unknown:
        raise ValueError(f"unknown resolution(s) {', '.join(unknown)}; known: {', '.join(Resolution)}")
    return frozenset(Resolution(n) for n in names)


def deviation(ev, r: Resolution, applies: bool) -> bool:
    """A branch where resolution ``r`` changes the paper's line: returns ``applies`` and, when it does,
    shows the deviation by name in the explanation."""
    if applies and ev.active:
        ev.test(f"deviation {r.value}", True, RESOLUTIONS[r])
    return applies
