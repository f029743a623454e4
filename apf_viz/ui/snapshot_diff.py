"""What a robot's snapshot saw, robot by robot, against where those robots are now.

A snapshot is identity-free (offsets and lights in the robot's own frame: all the algorithm may know),
but the person watching wants names: "robot 1: seen at (0, 4), now at (-1, 4)". The engine records who
was seen at each Look (``EngineState.seen``) and every move since (the history), which is enough to
put each seen robot where it stood at that Look. Stale means another robot's position or light differs
from what the snapshot holds; the robot's own light does not count, nor robots that came into sight since.
"""

from __future__ import annotations

from typing import NamedTuple

from apf_viz.core.engine import Engine
from apf_viz.core.grid import Point
from apf_viz.core.portrayal import in_frame


class SeenRobot(NamedTuple):
    """One robot of a snapshot: where and with which light it was seen, and where and how it is now."""

    robot: int
    seen_at: Point
    seen_light: str
    now_at: Point
    now_light: str

    @property
    def changed(self) -> bool:
        return self.seen_at != self.now_at or self.seen_light != self.now_light

    def describe(self) -> str:
        """ "robot 1: seen at (0, 4), now at (-1, 4)" / "robot 2: seen with light off, now leader1"."""
        parts = []
        if self.seen_at != self.now_at:
            parts.append(f"seen at {_p(self.seen_at)}, now at {_p(self.now_at)}")
        if self.seen_light != self.now_light:
            parts.append(f"seen with light {self.seen_light}, now {self.now_light}")
        return f"robot {self.robot}: " + "; ".join(parts)


def _p(p: Point) -> str:
    return f"({p[0]}, {p[1]})"


def seen_robots(engine: Engine, robot: int, start: list[Point]) -> list[SeenRobot]:
    """The robots in ``robot``'s held snapshot (empty if it holds none), in the snapshot's order.

    ``start``: the run's start positions (a robot that has not moved since the start stands there).
    A robot that holds a snapshot has not moved since its Look (a Move ends the cycle), so its current
    position is the snapshot's origin."""
    st = engine.state
    snap, ids = st.snapshot[robot], st.seen[robot]
    if snap is None or ids is None:
        return []
    pts = engine.current_points()
    look = int(st.look_step[robot])  # 1-based: the Look is in step ``look - 1``
    steps = engine.history.steps
    watched = set(ids)
    moved = {
        ev.robot
        for s in steps[look : engine.step_index]
        for ev in s.events
        if _moved(ev) and ev.robot in watched
    }
    at_look = {j: pts[j] for j in ids if j not in moved}
    missing = set(moved)
    for i in range(look - 1, -1, -1):  # back from the Look: each mover's last move before it
        if not missing:
            break
        for ev in reversed(steps[i].events):
            if ev.robot in missing and _moved(ev):
                at_look[ev.robot] = tuple(ev.to)  # type: ignore[assignment]
                missing.discard(ev.robot)
    for j in missing:
        at_look[j] = tuple(start[j])  # type: ignore[assignment]
    places = in_frame(snap.offsets(), pts[robot], engine.y_up[robot])
    light_at = {p: s.light for p, s in zip(places, snap.robots, strict=True)}
    by_place = {at_look[j]: j for j in ids}
    return [
        SeenRobot(by_place[p], p, light_at[p], pts[by_place[p]], st.lights[by_place[p]])
        for p in places
        if p in by_place
    ]


def _moved(ev) -> bool:
    return ev.phase == "move" and not ev.collision
