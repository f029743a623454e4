"""The algorithm of Kundu, Goswami, Ghosh and Sau, *Arbitrary pattern formation by asynchronous opaque
robots on infinite grid*: Phase 1 (Algorithm 1), Phase 2 (Algorithm 2) and Pattern Formation from Leader
Configuration (Algorithm 3), with exactly the paper's 8 lights.

The paper never says how a robot knows which procedure applies; :func:`dispatch` is our answer, read off
the robot's own light and the lights it sees (docs/ALGORITHM.md, "Phase dispatch").
"""

from __future__ import annotations

from apf_viz.algorithms.apf_opaque_grid import paper, portrayal, watches
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
from apf_viz.algorithms.apf_opaque_grid.resolutions import (
    ALL,
    G1,
    G2,
    G3,
    LA,
    LITERAL,
    LW,
    RESOLUTIONS,
    Resolution,
    Resolutions,
    deviation,
    parse_resolutions,
)
from apf_viz.core.algorithm import NOTHING, Decision, Pattern
from apf_viz.core.portrayal import (
    NO_EVIDENCE,
    Configuration,
    Evidence,
    Explanation,
    LightStyle,
    Overlays,
    Pseudocode,
)
from apf_viz.core.view import Snapshot

LIGHTS = ("off", "terminal1", "symmetric", "decider", "call", "leader1", "leader", "done")
LEADERS = {"leader1", "leader"}

__all__ = ["LIGHTS", "RESOLUTIONS", "ApfOpaqueGrid", "Resolution", "dispatch", "embedded_targets"]


def dispatch(view: Snapshot, pattern: Pattern, res: Resolutions, ev: Evidence = NO_EVIDENCE) -> Decision:
    """Which procedure a robot runs, decided from its light and the lights it sees."""
    light = view.light
    if light == "done":
        return stay(view, "done: stay", "done", NOTHING)
    seen = view.lights()
    if light == "leader":
        return pattern_formation_leader(view, pattern, res, ev)
    if light == "leader1":
        if G3 in res and deviation(ev, G3, "leader" in seen):
            return Decision("off", None, "leader1: a leader is visible → off (G3)", "A2.leader1.G3-off")
        if LW in res and deviation(ev, LW, any(s.dx < 0 and s.light in LEADERS for s in view.robots)):
            return Decision(
                "off", None, "leader1: a leader1/leader to my left → off (LW)", "A2.leader1.LW-off"
            )
        return phase2_leader1(view, res, ev)
    if light == "decider":
        if G3 in res and deviation(ev, G3, bool(seen & LEADERS)):
            return Decision(
                "off", None, "decider: a leader1/leader is visible → off (G3)", "A2.decider.G3-off"
            )
        return phase2_decider(view, res, ev)
    if light == "call":
        return phase2_call(view, res, ev)
    if light in ("terminal1", "symmetric"):
        if G2 in res and deviation(ev, G2, bool(seen & LEADERS)):
            rule_id = "A1.terminal1.G2-off" if light == "terminal1" else "A1.symmetric.G2-off"
            return Decision("off", None, f"{light}: a leader1/leader is visible → off (G2)", rule_id)
        return phase1_terminal1(view, res, ev) if light == "terminal1" else phase1_symmetric(view, res, ev)
    # light == "off"
    if ev.test("a leader or done robot in sight", bool(seen & {"leader", "done"}), "Phase 3 has begun"):
        return pattern_formation_off(view, pattern, res, ev)
    if ev.test("two deciders on L_I", two_deciders_on_left_line(view), "Phase 2 has begun to my left"):
        return phase2_off(view, res, ev)
    if G1 in res and deviation(ev, G1, bool(seen - {"off", "terminal1"})):
        return stay(
            view,
            "off: Phase 1 is over (a later light is visible) → wait (G1)",
            "A1.off.G1-wait",
            watches.g1_wait(view),
        )
    decision = phase1_off(view, res, ev)
    if G1 in res and decision.move is None and decision.light == "off":
        return stay(view, decision.rule, decision.rule_id, watches.phase1_wait(view))
    return decision


def _listed(names: list[str]) -> str:
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]


class ApfOpaqueGrid:
    """The paper's algorithm with a chosen set of resolutions (see :data:`RESOLUTIONS`).

    ``apf-opaque-grid`` enables all of them; ``apf-opaque-grid-literal`` only LA, which any run needs to
    finish; ``apf-opaque-grid@G1,G2`` enables exactly the ones listed. It describes itself to the
    screen (:mod:`apf_viz.core.portrayal`): a legend, overlays, and :meth:`explain`."""

    lights = LIGHTS

    def __init__(self, resolutions: Resolutions | set[str] | frozenset[str] = ALL) -> None:
        self.resolutions: Resolutions = parse_resolutions(set(resolutions))
        if self.resolutions == ALL:
            self.name = "apf-opaque-grid"
        elif self.resolutions == LITERAL:
            self.name = "apf-opaque-grid-literal"
        else:
            self.name = "apf-opaque-grid@" + ",".join(r for r in Resolution if r in self.resolutions)

    def decide(self, view: Snapshot, pattern: Pattern) -> Decision:
        return dispatch(view, pattern, self.resolutions)

    def explain(self, view: Snapshot, pattern: Pattern) -> Explanation:
        """The decision of :meth:`decide` on this view, with the predicates and regions it tested."""
        ev = Evidence()
        return ev.explanation(dispatch(view, pattern, self.resolutions, ev))

    def legend(self) -> dict[str, LightStyle]:
        return dict(portrayal.LEGEND)

    def overlays(self, config: Configuration) -> Overlays:
        return portrayal.overlays(config)

    def stage(self, config: Configuration) -> str:
        return portrayal.stage(config.positions, config.lights)

    def rules(self) -> dict[str, str]:
        """Every rule id a decision carries, with its words (rules.py)."""
        from apf_viz.algorithms.apf_opaque_grid.rules import RULE_IDS

        return dict(RULE_IDS)

    def pseudocode(self) -> Pseudocode:
        """The paper's algorithms with this variant's resolutions in place (the Paper panel)."""
        return paper.pseudocode(self.resolutions)

    def title(self) -> str:
        """This variant in words: the paper as written (with LA, which every run needs to finish), plus
        the resolutions it adds, or all of them but those it leaves out, whichever is shorter."""
        if self.resolutions == ALL:
            return "the default algorithm (every resolution)"
        added = [r.value for r in Resolution if r in self.resolutions - LITERAL]
        missing = [r.value for r in Resolution if r in ALL - self.resolutions]
        if not added:
            return "the paper as written" + ("" if LA in self.resolutions else " (without LA)")
        if len(missing) < len(added):
            return "every resolution but " + _listed(missing)
        noun = "resolution" if len(added) == 1 else "resolutions"
        return f"the paper as written with {noun} {_listed(added)}"

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
