"""Two small algorithms that prove the plug-in seam (the paper's algorithm lives in its own module).

Both are pure functions of the snapshot, as every algorithm must be. :class:`CompactLeft` also shows the
optional half (:mod:`apf_viz.core.portrayal`): its own legend and one overlay; :class:`Stay` shows none
and gets the defaults.
"""

from __future__ import annotations

from apf_viz.core.algorithm import Decision, Pattern
from apf_viz.core.grid import Direction
from apf_viz.core.portrayal import Configuration, LightStyle, Line, Overlays
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
                "off",
                Direction.LEFT,
                "someone is to my left and my left point is free: move left",
                "compact-left.slide",
            )
        return Decision(
            "done", None, "nothing to my left, or my left point is taken: stay, done", "compact-left.done"
        )

    def legend(self) -> dict[str, LightStyle]:
        return {
            "off": LightStyle((0, 150, 220), "still sliding left"),
            "done": LightStyle((240, 170, 0), "nothing to slide towards: done"),
        }

    def overlays(self, config: Configuration) -> Overlays:
        """The wall the robots slide towards: the leftmost occupied column."""
        wall = min(x for x, _ in config.positions)
        everyone_done = set(config.lights) == {"done"}
        return Overlays(
            (Line("x", wall, "the wall: the leftmost column", (0, 120, 200)),),
            "every robot done" if everyone_done else "sliding left",
        )
