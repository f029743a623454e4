"""Drafts of a start and a pattern, every change undoable, and what makes them a run (sizes, Theorem 1).
The shapes themselves are pure functions (core/shapes.py); workbench/studio.py turns gestures into them."""

from __future__ import annotations

from collections.abc import Sequence

from apf_viz.core.formats import size_problem
from apf_viz.core.grid import Point, as_point
from apf_viz.core.pattern_match import matches_pattern
from apf_viz.core.symmetry import describe_axis, unsolvable_axis

UNDO_DEPTH = 200  # drafts kept for Undo

Draft = tuple[tuple[Point, ...], tuple[bool, ...], tuple[Point, ...]]  # robots, their flips, pattern


def draft_of(robots: Sequence[Point], y_up: Sequence[bool], pattern: Sequence[Point]) -> Draft:
    """Robots, flips and pattern as a :data:`Draft` (points as tuples, so that drafts compare)."""
    return tuple((p[0], p[1]) for p in robots), tuple(y_up), tuple((p[0], p[1]) for p in pattern)


class Editor:
    """The robots and pattern being drawn, and their history (Undo / Redo). Nothing here touches the
    run: the session starts a run from the drafts once :meth:`problem` has nothing to say."""

    def __init__(self, robots: Sequence[Point], y_up: Sequence[bool], pattern: Sequence[Point]) -> None:
        self.robots: list[Point] = [as_point(p) for p in robots]
        self.y_up: list[bool] = list(y_up)
        self.pattern: list[Point] = [as_point(p) for p in pattern]
        self._undo: list[Draft] = []
        self._redo: list[Draft] = []
        self._gesture: Draft | None = None  # the draft before a gesture in progress (a drag)

    # ------------------------------------------------------------------ history
    @property
    def draft(self) -> Draft:
        """The drafts as they are now, comparable with :func:`draft_of` a run's start and pattern."""
        return tuple(self.robots), tuple(self.y_up), tuple(self.pattern)

    def _restore(self, draft: Draft) -> None:
        robots, y_up, pattern = draft
        self.robots, self.y_up, self.pattern = list(robots), list(y_up), list(pattern)

    def _record(self) -> None:
        """Keep the draft as it is before a change (a new change forgets what Redo had). During a gesture
        it was kept once, when the gesture began: one Undo takes back the whole drag."""
        if self._gesture is not None:
            return
        self._undo = [*self._undo[-(UNDO_DEPTH - 1) :], self.draft]
        self._redo = []

    def begin_gesture(self) -> None:
        """A drag begins: its changes, however many, are one step of the history."""
        self.end_gesture()
        self._record()
        self._gesture = self.draft

    def end_gesture(self) -> None:
        """The drag ends; a drag that changed nothing leaves no step in the history."""
        if self._gesture is None:
            return
        unchanged = self.draft == self._gesture
        self._gesture = None
        if unchanged and self._undo and self._undo[-1] == self.draft:
            self._undo.pop()

    def undo(self) -> str:
        self.end_gesture()
        if not self._undo:
            return "nothing to undo"
        self._redo.append(self.draft)
        self._restore(self._undo.pop())
        return "undone"

    def redo(self) -> str:
        if not self._redo:
            return "nothing to redo"
        self._undo.append(self.draft)
        self._restore(self._redo.pop())
        return "redone"

    def start_from(self, robots: Sequence[Point], y_up: Sequence[bool], pattern: Sequence[Point]) -> bool:
        """A new run's start and pattern become the drafts; the drafts as they were go into the history,
        so one Undo brings back what was drawn (a Demo or a file loaded over a drawing never loses it).
        Returns whether the drafts changed."""
        new = draft_of(robots, y_up, pattern)
        if new == self.draft:
            return False
        self._record()
        self._restore(new)
        return True

    # ------------------------------------------------------------------ changes
    def set_pattern(self, cells: Sequence[Point], said: str) -> str:
        """The pattern becomes ``cells`` (distinct, in drawing order); one Undo brings the old one back."""
        cells = [as_point(p) for p in dict.fromkeys(cells)]
        if cells == self.pattern:
            return f"{said}: nothing changed"
        self._record()
        self.pattern = cells
        return said

    def set_robots(self, cells: Sequence[Point], said: str) -> str:
        """The robots stand on ``cells``; a robot that stays keeps its flip, a new one has +y up."""
        cells = [as_point(p) for p in dict.fromkeys(cells)]
        if cells == self.robots:
            return f"{said}: nothing changed"
        flips = dict(zip(self.robots, self.y_up, strict=True))
        self._record()
        self.robots = cells
        self.y_up = [flips.get(p, True) for p in cells]
        return said

    def toggle_target(self, cell: Point) -> str:
        if cell in self.pattern:
            return self.set_pattern([p for p in self.pattern if p != cell], f"removed target {cell}")
        return self.set_pattern([*self.pattern, cell], f"added target {cell}")

    def toggle_robot(self, cell: Point) -> str:
        if cell in self.robots:
            return self.set_robots([p for p in self.robots if p != cell], f"removed robot {cell}")
        return self.set_robots([*self.robots, cell], f"added robot {cell}")

    def flip_robot(self, cell: Point) -> str:
        """The adversary's choice for the robot there: its y-axis up or down."""
        if cell not in self.robots:
            return f"no robot at {cell} to flip"
        self._record()
        i = self.robots.index(cell)
        self.y_up[i] = not self.y_up[i]
        return f"robot {cell}: +y {'up' if self.y_up[i] else 'down'}"

    def move_robot(self, start: Point, end: Point) -> str:
        """The robot at ``start`` to ``end`` in one action, its flip kept."""
        if start not in self.robots:
            return f"no robot at {start}"
        if end in self.robots:
            return f"{end} holds a robot already"
        self._record()
        self.robots[self.robots.index(start)] = end
        return f"moved the robot at {start} to {end}"

    def clear_pattern(self) -> None:
        self.set_pattern([], "cleared")

    # ------------------------------------------------------------------ what the drafts make
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
