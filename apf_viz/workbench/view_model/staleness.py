"""What a robot's snapshot saw, robot by robot, against where those robots are now: the one notion of a
stale snapshot, used by the Selected robot caption (the snapshot it holds) and by Why (the snapshot its
last decision was made on), in the same words.

A snapshot is identity-free (offsets and lights in the robot's own frame: all the algorithm may know),
but the person watching wants names: "robot 1: seen at (0, 4), now at (-1, 4)". The engine records who
was seen at each Look (``EngineState.seen``, and ``decided_seen`` for the Look a decision used) and every
move since (the history), which is enough to put each seen robot where it stood at that Look. Stale
means another robot's position or light differs from what the snapshot holds; the robot's own light does
not count, nor robots that came into sight since.
"""

from __future__ import annotations

from typing import Literal, NamedTuple

from apf_viz.core.engine import Engine
from apf_viz.core.grid import Point, hiders
from apf_viz.core.portrayal import in_frame

Which = Literal["held", "decided"]


class SeenRobot(NamedTuple):
    """One robot of a snapshot: where and with which light it was seen, and where and how it is now."""

    robot: int
    seen_at: Point
    seen_light: str
    now_at: Point
    now_light: str

    @property
    def changed(self) -> bool:
        """Whether the robot has moved or changed its light since it was seen."""
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


def seen_robots(
    engine: Engine, robot: int, which: Which = "held", now: list[Point] | None = None
) -> list[SeenRobot]:
    """The robots of ``robot``'s snapshot, in the snapshot's order: the one it holds (``held``; empty if
    it holds none) or the one its latest decision was computed on (``decided``; empty before it).

    ``now``: the current positions, when the caller has them already."""
    st = engine.state
    if which == "held":
        snap, ids, look = st.snapshot[robot], st.seen[robot], int(st.look_step[robot])
    else:
        snap, ids, look = st.decided[robot], st.decided_seen[robot], int(st.decided_look[robot])
    if snap is None or ids is None or look < 1 or look > engine.step_index:
        return []
    pts = now if now is not None else engine.current_points()
    at_look = _positions_at(engine, set(ids) | {robot}, look)
    places = in_frame(snap.offsets(), at_look[robot], engine.y_up[robot])
    light_at = {p: s.light for p, s in zip(places, snap.robots, strict=True)}
    by_place = {at_look[j]: j for j in ids}
    return [
        SeenRobot(by_place[p], p, light_at[p], pts[by_place[p]], st.lights[by_place[p]])
        for p in places
        if p in by_place
    ]


def changes(
    engine: Engine, robot: int, which: Which = "held", now: list[Point] | None = None
) -> list[SeenRobot]:
    """The robots of that snapshot that have moved or changed light since its Look: what makes it stale."""
    return [s for s in seen_robots(engine, robot, which, now) if s.changed]


def hidden_from(engine: Engine, robot: int, now: list[Point]) -> dict[int, int]:
    """The robots ``robot`` does not see, each with the robot that hides it: at the Look of the
    snapshot it holds (positions as they stood then), or, holding none, now."""
    st = engine.state
    look = int(st.look_step[robot])
    if st.snapshot[robot] is None or look < 1 or look > engine.step_index:
        return hiders(now, robot)
    at_look = _positions_at(engine, set(range(engine.k)), look)
    return hiders([at_look[j] for j in range(engine.k)], robot)


def stale_holders(engine: Engine, now: list[Point]) -> list[int]:
    """Every robot holding a snapshot in which another robot has since moved or changed light."""
    holding = [r for r in range(engine.k) if engine.state.snapshot[r] is not None]
    return [r for r in holding if changes(engine, r, "held", now)]


def _positions_at(engine: Engine, robots: set[int], look: int) -> dict[int, Point]:
    """Where each of ``robots`` stood at the Look of step ``look`` (1-based: the Look is in step
    ``look - 1``, and a step's events are of one phase, so no robot moves in it)."""
    points = engine.history.positions_after(look)
    return {j: (int(points[j, 0]), int(points[j, 1])) for j in robots}
