"""The snapshot a robot gets from a Look: the only thing an algorithm ever receives.

It holds, in the robot's own frame (itself at the origin, x agreed, y possibly flipped), the offset and the
light of every robot it can see, and its own light. Nothing else: no global coordinate, no id, no robot
count. Visible robots are sorted by offset (dx, then dy), so the order itself carries no identity, and
algorithms may rely on it (the robots of one vertical line are a contiguous run).
"""

from __future__ import annotations

from typing import NamedTuple

from apf_viz.core.grid import Point


class Seen(NamedTuple):
    """One visible robot: offset (dx, dy) in the observer's frame, and its light."""

    dx: int
    dy: int
    light: str


class Snapshot(NamedTuple):
    """What one Look returns. Hashable, so identical views share one cached decision."""

    light: str
    robots: tuple[Seen, ...]

    def at(self, dx: int, dy: int) -> Seen | None:
        """The visible robot at this offset, if any."""
        for s in self.robots:
            if s.dx == dx and s.dy == dy:
                return s
        return None

    def offsets(self) -> list[Point]:
        return [(s.dx, s.dy) for s in self.robots]

    def lights(self) -> set[str]:
        return {s.light for s in self.robots}
