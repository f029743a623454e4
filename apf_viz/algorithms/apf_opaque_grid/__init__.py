"""The algorithm of Kundu, Goswami, Ghosh and Sau, *Arbitrary pattern formation by asynchronous opaque
robots on infinite grid*: Phase 1 (Algorithm 1), Phase 2 (Algorithm 2) and Pattern Formation from Leader
Configuration (Algorithm 3), with exactly the paper's 8 lights.

The paper never says how a robot knows which procedure applies; :func:`dispatch` is our answer, read off
the robot's own light and the lights it sees (docs/ALGORITHM.md, "Phase dispatch").
"""

from __future__ import annotations

from apf_viz.algorithms.apf_opaque_grid.pattern_formation import (
    embedded_targets,
    pattern_formation_leader,
    pattern_formation_off,
)
from apf_viz.algorithms.apf_opaque_grid.phase1 import phase1_off, phase1_symmetric, phase1_terminal1, stay
from apf_viz.algorithms.apf_opaque_grid.phase2 import (
    phase2_call,
    phase2_decider,
    phase2_leader1,
    phase2_off,
    two_deciders_on_left_line,
)
from apf_viz.algorithms.apf_opaque_grid.predicates import lights_of
from apf_viz.algorithms.apf_opaque_grid.resolutions import ALL, LITERAL, RESOLUTIONS
from apf_viz.core.algorithm import Decision, Pattern
from apf_viz.core.view import Snapshot

LIGHTS = ("off", "terminal1", "symmetric", "decider", "call", "leader1", "leader", "done")
LEADERS = {"leader1", "leader"}

__all__ = ["LIGHTS", "RESOLUTIONS", "ApfOpaqueGrid", "dispatch", "embedded_targets"]


def dispatch(view: Snapshot, pattern: Pattern, res: frozenset[str]) -> Decision:
    """Which procedure a robot runs, decided from its light and the lights it sees."""
    light = view.light
    if light == "done":
        return stay(view, "done: stay")
    seen = lights_of(view.robots)
    if light == "leader":
        return pattern_formation_leader(view, pattern, res)
    if light == "leader1":
        if "G3" in res and "leader" in seen:
            return Decision("off", None, "leader1: a leader is visible → off (G3)")
        if "LW" in res and any(s.dx < 0 and s.light in LEADERS for s in view.robots):
            return Decision("off", None, "leader1: a leader1/leader to my left → off (LW)")
        return phase2_leader1(view, res)
    if light == "decider":
        if "G3" in res and seen & LEADERS:
            return Decision("off", None, "decider: a leader1/leader is visible → off (G3)")
        return phase2_decider(view, res)
    if light == "call":
        return phase2_call(view, res)
    if light in ("terminal1", "symmetric"):
        if "G2" in res and seen & LEADERS:
            return Decision("off", None, f"{light}: a leader1/leader is visible → off (G2)")
        return phase1_terminal1(view, res) if light == "terminal1" else phase1_symmetric(view, res)
    # light == "off"
    if seen & {"leader", "done"}:
        return pattern_formation_off(view, pattern, res)
    if two_deciders_on_left_line(view):
        return phase2_off(view, res)
    if "G1" in res and seen - {"off", "terminal1"}:
        return stay(view, "off: Phase 1 is over (a later light is visible) → wait (G1)")
    return phase1_off(view, res)


class ApfOpaqueGrid:
    """The paper's algorithm with a chosen set of resolutions (see :data:`RESOLUTIONS`).

    ``apf-opaque-grid`` enables all of them; ``apf-opaque-grid-literal`` only LA, which any run needs to
    finish; ``apf-opaque-grid@G1,G2`` enables exactly the ones listed."""

    lights = LIGHTS

    def __init__(self, resolutions: frozenset[str] | set[str] = ALL) -> None:
        unknown = set(resolutions) - set(RESOLUTIONS)
        if unknown:
            raise ValueError(
                f"unknown resolution(s) {', '.join(sorted(unknown))}; known: {', '.join(RESOLUTIONS)}"
            )
        self.resolutions = frozenset(resolutions)
        if self.resolutions == ALL:
            self.name = "apf-opaque-grid"
        elif self.resolutions == LITERAL:
            self.name = "apf-opaque-grid-literal"
        else:
            self.name = "apf-opaque-grid@" + ",".join(r for r in RESOLUTIONS if r in self.resolutions)

    def decide(self, view: Snapshot, pattern: Pattern) -> Decision:
        return dispatch(view, pattern, self.resolutions)

    @classmethod
    def parse(cls, name: str) -> ApfOpaqueGrid:
        """Build from a registry name: the two variants, or ``apf-opaque-grid@R1,R2`` (``@`` alone: none)."""
        if name == "apf-opaque-grid":
            return cls(ALL)
        if name == "apf-opaque-grid-literal":
            return cls(LITERAL)
        prefix = "apf-opaque-grid@"
        if name.startswith(prefix):
            listed = {r.strip() for r in name[len(prefix) :].split(",") if r.strip()}
            return cls(listed)
        raise ValueError(f"not a variant of apf-opaque-grid: {name!r}")
