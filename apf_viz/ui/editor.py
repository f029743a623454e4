"""Drafts of a start and a pattern, drawn by clicks, and what makes them a run (sizes, Theorem 1)."""

from __future__ import annotations

from collections.abc import Sequence

from apf_viz.core.formats import size_problem
from apf_viz.core.grid import Point
from apf_viz.core.pattern_match import matches_pattern
from apf_viz.core.symmetry import describe_axis, unsolvable_axis


class Editor:
    """The robots and pattern being drawn. Nothing here touches the run: the session starts a run from
    the drafts once :meth:`problem` has nothing to say."""

    def __init__(self, robots: Sequence[Point], y_up: Sequence[bool], pattern: Sequence[Point]) -> None:
        self.robots: list[Point] = [tuple(p) for p in robots]
        self.y_up: list[bool] = list(y_up)
        self.pattern: list[Point] = [tuple(p) for p in pattern]

    def toggle_target(self, cell: Point) -> str:
        if cell in self.pattern:
            self.pattern.remove(cell)
            return f"removed target {cell}"
        self.pattern.append(cell)
        return f"added target {cell}"

    def cycle_robot(self, cell: Point) -> str:
        """Empty → robot (y up) → robot (y flipped) → empty."""
        if cell not in self.robots:
            self.robots.append(cell)
            self.y_up.append(True)
            return f"added robot {cell}"
        i = self.robots.index(cell)
        if self.y_up[i]:
            self.y_up[i] = False
            return f"robot {cell}: y-axis flipped"
        del self.robots[i]
        del self.y_up[i]
        return f"removed robot {cell}"

    def clear_pattern(self) -> None:
        self.pattern = []

    def axis(self) -> float | None:
        """The unsolvable symmetry axis of the drafted robots (Theorem 1), if any."""
        axis = unsolvable_axis(self.robots)
        return float(axis) if axis is not None else None

    def problem(self) -> str | None:
        """Why the drafts cannot start a run, or None."""
        if not self.robots:
            return "place at least one robot"
        sizes = size_problem(len(self.pattern), len(self.robots))
        if sizes:
            return sizes
        axis = unsolvable_axis(self.robots)
        if axis is not None and not matches_pattern(self.robots, self.pattern):
            return (
                f"unsolvable start: the robots are mirror-symmetric about {describe_axis(axis)}, "
                "a horizontal line through no robot (Theorem 1); move or add a robot to break the symmetry"
            )
        return None
