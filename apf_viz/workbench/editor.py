"""Drafts of a start and a pattern, every change undoable, and what makes them a run (sizes, Theorem 1).
The shapes themselves are pure functions (core/shapes.py); workbench/studio.py turns gestures into them."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from apf_viz.core.formats import InputError, size_problem
from apf_viz.core.grid import Point, as_point
from apf_viz.core.pattern_match import matches_pattern
from apf_viz.core.symmetry import describe_axis, unsolvable_axis

UNDO_DEPTH = 200  # changes kept for Undo (each one what it changed, not a copy of the drafts)
MAX_DRAWN = 10_000
"""Cells a drawing holds at most, in the pattern and in the robots each (as many as the largest shape one
gesture draws, core/shapes.MAX_SIZE): past it a change is refused in one line (docs/GUIDE.md). A run of
more robots than a page plays is no drawing; tests/test_studio.py draws at the bound and measures."""

Draft = tuple[tuple[Point, ...], tuple[bool, ...], tuple[Point, ...]]  # robots, their flips, pattern


@dataclass(frozen=True)
class Splice:
    """What a change did to one list: at ``at``, ``before`` became ``after`` (the rest, before and after
    them, unchanged). A cell painted or erased is a splice of one cell, whatever the drawing's size."""

    at: int
    before: tuple[Any, ...]
    after: tuple[Any, ...]

    @classmethod
    def between(cls, old: Sequence[Any], new: Sequence[Any]) -> Splice | None:
        """The smallest splice that makes ``new`` of ``old`` (None: they are equal)."""
        n = min(len(old), len(new))
        head = 0
        while head < n and old[head] == new[head]:
            head += 1
        if head == len(old) == len(new):
            return None
        tail = 0
        while tail < n - head and old[len(old) - 1 - tail] == new[len(new) - 1 - tail]:
            tail += 1
        return cls(head, tuple(old[head : len(old) - tail]), tuple(new[head : len(new) - tail]))

    def undone(self, now: list[Any]) -> list[Any]:
        """The list as it was before the change, from the list ``now`` after it."""
        return [*now[: self.at], *self.before, *now[self.at + len(self.after) :]]

    def redone(self, then: list[Any]) -> list[Any]:
        """The list as it is after the change, from the list ``then`` before it."""
        return [*then[: self.at], *self.after, *then[self.at + len(self.before) :]]


Change = tuple[Splice | None, Splice | None, Splice | None]  # what one change did: robots, flips, pattern


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
        self._undo: list[Change] = []
        self._redo: list[Change] = []
        self._before: Draft | None = None  # the drafts before the change being made, until it is kept
        self._gesture = False  # a drag in progress: its changes are one step of the history

    # ------------------------------------------------------------------ history
    @property
    def draft(self) -> Draft:
        """The drafts as they are now, comparable with :func:`draft_of` a run's start and pattern."""
        return tuple(self.robots), tuple(self.y_up), tuple(self.pattern)

    def _restore(self, draft: Draft) -> None:
        robots, y_up, pattern = draft
        self.robots, self.y_up, self.pattern = list(robots), list(y_up), list(pattern)

    def _record(self) -> None:
        """Before a change: keep what the change before it did (a new change forgets what Redo had).
        During a gesture the drafts were kept once, when it began: one Undo takes back the whole drag."""
        if self._gesture:
            return
        self._keep()
        self._before = self.draft
        self._redo = []

    def _keep(self) -> None:
        """The change since :meth:`_record` as what it did (a change that did nothing is no step)."""
        if self._before is None:
            return
        robots, y_up, pattern = self._before
        self._before = None
        change = (
            Splice.between(robots, self.robots),
            Splice.between(y_up, self.y_up),
            Splice.between(pattern, self.pattern),
        )
        if change != (None, None, None):
            self._undo = [*self._undo[-(UNDO_DEPTH - 1) :], change]

    def begin_gesture(self) -> None:
        """A drag begins: its changes, however many, are one step of the history."""
        self.end_gesture()
        self._record()
        self._gesture = True

    def end_gesture(self) -> None:
        """The drag ends; a drag that changed nothing leaves no step in the history."""
        self._gesture = False

    def undo(self) -> str:
        """Take back the last change (a drag in progress ends first); returns what was done in words."""
        self.end_gesture()
        self._keep()
        if not self._undo:
            return "nothing to undo"
        change = self._undo.pop()
        self._apply(change, undo=True)
        self._redo.append(change)
        return "undone"

    def redo(self) -> str:
        """Make again the last change undone; returns what was done in words."""
        self._keep()
        if not self._redo:
            return "nothing to redo"
        change = self._redo.pop()
        self._apply(change, undo=False)
        self._undo.append(change)
        return "redone"

    def _apply(self, change: Change, undo: bool) -> None:
        robots, y_up, pattern = change
        if robots is not None:
            self.robots = robots.undone(self.robots) if undo else robots.redone(self.robots)
        if y_up is not None:
            self.y_up = y_up.undone(self.y_up) if undo else y_up.redone(self.y_up)
        if pattern is not None:
            self.pattern = pattern.undone(self.pattern) if undo else pattern.redone(self.pattern)

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
        _bounded(len(cells), "the pattern")
        self._record()
        self.pattern = cells
        return said

    def set_robots(self, cells: Sequence[Point], said: str) -> str:
        """The robots stand on ``cells``; a robot that stays keeps its flip, a new one has +y up."""
        cells = [as_point(p) for p in dict.fromkeys(cells)]
        if cells == self.robots:
            return f"{said}: nothing changed"
        _bounded(len(cells), "the robots")
        flips = dict(zip(self.robots, self.y_up, strict=True))
        self._record()
        self.robots = cells
        self.y_up = [flips.get(p, True) for p in cells]
        return said

    def toggle_target(self, cell: Point) -> str:
        """A target at ``cell`` removed if there is one, else added; returns what was done in words."""
        if cell in self.pattern:
            return self.set_pattern([p for p in self.pattern if p != cell], f"removed target {cell}")
        return self.set_pattern([*self.pattern, cell], f"added target {cell}")

    def toggle_robot(self, cell: Point) -> str:
        """A robot at ``cell`` removed if there is one, else added (+y up); returns what was done in words."""
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
        """Every target removed (one Undo brings them back)."""
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


def _bounded(cells: int, what: str) -> None:
    if cells > MAX_DRAWN:
        raise InputError(f"{what} would have {cells:,} cells; a drawing holds at most {MAX_DRAWN:,}")
