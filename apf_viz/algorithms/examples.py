"""Two small algorithms that prove the plug-in seam (the paper's algorithm lives in its own module).

Both are pure functions of the snapshot, as every algorithm must be.
"""

from __future__ import annotations

from apf_viz.core.algorithm import Decision, Pattern
from apf_viz.core.grid import Direction
from apf_viz.core.view import Snapshot


class Stay:
    """Every robot keeps its light and stays: the run ends at once, ``formed`` iff it starts formed."""

    name = "stay"
    lights = ("off",)

    def decide(self, view: Snapshot, pattern: Pattern) -> Decision:
        return Decision(view.light, None, "stay: nothing to do")


class CompactLeft:
    """Each robot slides left along its row while some robot is strictly to its left (its open left
    half is not empty) and the point to its left is free; a robot that cannot slide shows ``done``.

    Only leftward moves exist, so no robot can enter the point another robot saw free: the toy is
    collision-free even on stale snapshots. It forms a pattern only if the pattern is what the slide
    produces."""

    name = "compact-left"
    lights = ("off", "done")

    def decide(self, view: Snapshot, pattern: Pattern) -> Decision:
        anyone_left = any(s.dx < 0 for s in view.robots)
        blocked = view.at(-1, 0) is not None
        if anyone_left and not blocked:
            return Decision(
                "off", Direction.LEFT, "someone is to my left and my left point is free: move left"
            )
        return Decision("done", None, "nothing to my left, or my left point is taken: stay, done")
