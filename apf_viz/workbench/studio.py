"""The pattern studio's tool and a gesture in progress: what a click, a second click or a dragged box
does to the drafts (workbench/editor.py) in Edit pattern or Edit robots, through the pure shapes of
core/shapes.py. The same tools draw targets and starts."""

from __future__ import annotations

from typing import Literal

from apf_viz.core import shapes
from apf_viz.core.grid import Point
from apf_viz.core.symmetry import unsolvable_axis
from apf_viz.workbench.editor import Editor

# (tool, what it does), in the Tool dropdown's order.
TOOLS: dict[str, str] = {
    "cell": "click a cell: add or remove it",
    "box": "drag a box: fill it (Shift: erase it); a click toggles one cell",
    "line": "click two cells: every cell of the digital line between them",
    "outline": "click two corners: the rectangle's border",
    "ring": "click the centre: a ring of the size's radius",
    "disc": "click the centre: a filled disc of the size's radius",
    "row": "click the left end: a row of the size's length",
    "column": "click the bottom end: a column of the size's length",
    "staircase": "click the bottom step: a staircase of the size's steps",
    "text": "click the top-left: the text, in a 3×5 font",
    "move": "click a cell, then where it goes: a robot, or the whole pattern",
    "flip": "click a robot: its y-axis up or down (the adversary's choice)",
}
FIT_PATTERN, FIT_ROBOTS = "Fit pattern", "Fit robots"
TRANSFORMS = ("Mirror ↔", "Mirror ↕", "Rotate 90°", "Scale ×2", FIT_PATTERN, FIT_ROBOTS)
NUDGES = {"←": (-1, 0), "→": (1, 0), "↑": (0, 1), "↓": (0, -1)}  # the whole draft by one cell
Mode = Literal["edit-pattern", "edit-robots"]


class Studio:
    """The chosen tool, its size and text, and the first click of a two-click tool."""

    def __init__(self) -> None:
        self.tool = "cell"
        self.size = 4
        self.text = "APF"
        self.anchor: Point | None = None

    def choose(self, tool: str) -> None:
        if tool not in TOOLS:
            raise shapes.ShapeError(f"no tool {tool[:40]!r}; tools: {', '.join(TOOLS)}")
        self.tool, self.anchor = tool, None

    def click(self, editor: Editor, mode: Mode, cell: Point) -> str:
        """One click with the current tool; returns what it did."""
        tool = self.tool
        if tool == "flip":
            return editor.flip_robot(cell) if mode == "edit-robots" else "flip: robots only (Edit robots)"
        if tool in ("cell", "box"):
            return editor.toggle_robot(cell) if mode == "edit-robots" else editor.toggle_target(cell)
        if tool in ("line", "outline", "move"):
            if self.anchor is None:
                self.anchor = cell
                return f"{tool}: first point {cell}; click the second"
            first, self.anchor = self.anchor, None
            if tool == "move":
                return self._move(editor, mode, first, cell)
            drawn = shapes.line(first, cell) if tool == "line" else shapes.outline(first, cell)
            return self._add(editor, mode, drawn, f"{tool} {first}–{cell}")
        return self._add(editor, mode, self._placed(tool, cell), f"{tool} at {cell}")

    def _placed(self, tool: str, cell: Point) -> list[Point]:
        n = self.size
        if tool == "text":
            return shapes.text(self.text, cell)
        make = {
            "ring": shapes.ring,
            "disc": shapes.disc,
            "row": shapes.row,
            "column": shapes.column,
            "staircase": shapes.staircase,
        }[tool]
        return make(cell, n)

    def box(self, editor: Editor, mode: Mode, a: Point, b: Point, erase: bool) -> str:
        """A dragged box: filled, or (``erase``) emptied."""
        cells = shapes.box(a, b)
        what = f"{'erased' if erase else 'filled'} {a}–{b}"
        if erase:
            if mode == "edit-robots":
                return editor.set_robots(shapes.removed(editor.robots, cells), what)
            return editor.set_pattern(shapes.removed(editor.pattern, cells), what)
        return self._add(editor, mode, cells, what)

    def transform(self, editor: Editor, mode: Mode, name: str) -> str:
        """Mirror, rotate, scale the whole draft being edited; fit the pattern to the robots (cells added,
        never one removed) or the robots to the pattern (robots added or removed, the start kept solvable)."""
        cells = editor.robots if mode == "edit-robots" else editor.pattern
        if name == FIT_PATTERN:
            k = len(editor.robots)
            if len(editor.pattern) > k:
                return (
                    f"the pattern has {len(editor.pattern)} cells for {k} robots: nothing removed "
                    f"(Fit robots places {len(editor.pattern) - k} more robots; Erase removes cells)"
                )
            fitted, said = shapes.fitted(editor.pattern, k)  # cells added: there are no more than k
            return editor.set_pattern(fitted, f"the pattern fitted to {k} robots: {said}")
        if name == FIT_ROBOTS:
            n = len(editor.pattern)
            robots, said = shapes.robots_fitted(editor.robots, n, lambda r: unsolvable_axis(r) is None)
            return editor.set_robots(robots, f"the robots fitted to the {n}-cell pattern: {said}")
        if name in NUDGES:
            dx, dy = NUDGES[name]
            return self._set(editor, mode, shapes.translated(cells, dx, dy), f"moved {name}")
        changed = {
            "Mirror ↔": lambda c: shapes.mirrored(c, "x"),
            "Mirror ↕": lambda c: shapes.mirrored(c, "y"),
            "Rotate 90°": shapes.rotated,
            "Scale ×2": lambda c: shapes.scaled(c, 2),
        }
        if name not in changed:
            raise shapes.ShapeError(f"no transform {name[:40]!r}; transforms: {', '.join(TRANSFORMS)}")
        return self._set(editor, mode, changed[name](cells), name.lower())

    @staticmethod
    def _add(editor: Editor, mode: Mode, cells: list[Point], what: str) -> str:
        if mode == "edit-robots":
            return editor.set_robots(shapes.merged(editor.robots, cells), what)
        return editor.set_pattern(shapes.merged(editor.pattern, cells), what)

    @staticmethod
    def _set(editor: Editor, mode: Mode, cells: list[Point], what: str) -> str:
        if mode == "edit-robots":
            return editor.set_robots(cells, what)
        return editor.set_pattern(cells, what)

    @staticmethod
    def _move(editor: Editor, mode: Mode, first: Point, to: Point) -> str:
        if mode == "edit-robots":
            return editor.move_robot(first, to)
        dx, dy = to[0] - first[0], to[1] - first[1]
        return editor.set_pattern(
            shapes.translated(editor.pattern, dx, dy), f"moved the pattern by ({dx}, {dy})"
        )
