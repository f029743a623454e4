"""The pattern studio's tool and a gesture in progress: what a click, a second click, a dragged stroke or
a dragged box does to the drafts (workbench/editor.py) in Edit pattern or Edit robots, through the pure
shapes of core/shapes.py. The same tools draw targets and starts. The live mirror copies every cell a
tool draws or erases across the axes fixed when it was turned on."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Literal

from apf_viz.core import shapes
from apf_viz.core.grid import Point
from apf_viz.core.symmetry import unsolvable_axis
from apf_viz.workbench.editor import Editor
from apf_viz.workbench.selection import Selection

# (tool, what it does), in the Tool dropdown's order.
TOOLS: dict[str, str] = {
    "cell": "click a cell: add or remove it; drag: paint",
    "eraser": "click or drag: erase cells",
    "fill": "click inside a closed outline: fill it",
    "box": "drag from a cell to a cell: the box between, both included, filled (Shift: erased); a click "
    "toggles one cell",
    "select": "drag a box: select the cells in it (then Copy, Cut, Delete; Move all moves them)",
    "paste": "click: the copied cells, their bottom-left corner there",
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
MIRRORS = {"off": (False, False), "x ↔": (True, False), "y ↕": (False, True), "both": (True, True)}
PAINTING = ("cell", "eraser")  # the tools a drag paints with
TOOL_KEYS = {
    "cell": "C",
    "eraser": "E",
    "fill": "G",
    "box": "U",
    "select": "H",
    "line": "L",
    "text": "T",
    "move": "V",
}
"""A key per tool a pixel editor has (Aseprite's E eraser, G bucket, U rectangle, L line, T text, V move;
C the cell, H the selection: viser's camera takes W A S D Q, the run M, F, P, I, J, B and R)."""
CAUTION_CELLS = 500
"""A fit that adds more robots than this takes seconds (each new robot keeps the start solvable): the
first click says so, a second one goes on."""


class Studio:
    """The chosen tool, its size and text, and the first click of a two-click tool."""

    def __init__(self) -> None:
        self.tool = "cell"
        self.size = 4
        self.text = "APF"
        self.anchor: Point | None = None
        self.mirror = "off"
        self._axes: tuple[int | None, int | None] = (None, None)  # twice the mirror axes' x and y
        self.selection = Selection()
        self._caution: tuple[str, int, int] | None = None  # a slow fit asked once: (name, robots, cells)
        self._stroke: tuple[bool, Point] | None = None  # a drag in progress: (erasing, its last cell)
        self.said = ""  # what the last edit did, for the line under the tool

    def choose(self, tool: str) -> None:
        """Take ``tool`` (a two-click tool's first click forgotten); an unknown one is refused."""
        if tool not in TOOLS:
            raise shapes.ShapeError(f"no tool {tool[:40]!r}; tools: {', '.join(TOOLS)}")
        self.tool, self.anchor = tool, None

    # ------------------------------------------------------------------ the live mirror
    def set_mirror(self, editor: Editor, mode: Mode, which: str) -> str:
        """Turn the live mirror on about the middle of the draft being edited (its box's centre lines;
        the origin for an empty draft), or off."""
        if which not in MIRRORS:
            raise shapes.ShapeError(f"mirror {which[:20]!r}: choose {', '.join(MIRRORS)}")
        cells = _drawn(editor, mode)
        twice_x = min(x for x, _ in cells) + max(x for x, _ in cells) if cells else 0
        twice_y = min(y for _, y in cells) + max(y for _, y in cells) if cells else 0
        on_x, on_y = MIRRORS[which]
        self.mirror, self._axes = which, (twice_x if on_x else None, twice_y if on_y else None)
        if which == "off":
            return "mirror off"
        axes = [f"x = {twice_x / 2:g}" if on_x else "", f"y = {twice_y / 2:g}" if on_y else ""]
        return f"mirror on: every cell drawn is copied across {' and '.join(a for a in axes if a)}"

    @property
    def axes(self) -> tuple[float | None, float | None]:
        """The live mirror's axes (x of the vertical one, y of the horizontal one), None where off."""
        return tuple(None if a is None else a / 2 for a in self._axes)  # type: ignore[return-value]

    def _mirrored(self, cells: list[Point]) -> list[Point]:
        return shapes.reflected(cells, *self._axes)

    # ------------------------------------------------------------------ clicks
    def click(self, editor: Editor, mode: Mode, cell: Point) -> str:
        """One click with the current tool; returns what it did."""
        tool = self.tool
        if tool == "flip":
            return editor.flip_robot(cell) if mode == "edit-robots" else "flip: robots only (Edit robots)"
        if tool in ("cell", "box"):
            erase = cell in _drawn(editor, mode)
            what = f"{'removed' if erase else 'added'} {_noun(mode)} {cell}"
            return self._paint(editor, mode, [cell], erase, what)
        if tool == "eraser":
            return self._paint(editor, mode, [cell], True, f"erased {_noun(mode)} {cell}")
        if tool == "fill":
            return self._fill(editor, mode, cell)
        if tool == "select":
            self.selection.clear()
            return "select: drag a box over the cells to select"
        if tool == "paste":
            if not self.selection.clipboard:
                return "nothing copied: select cells, then Copy"
            return self._add(editor, mode, self.selection.pasted_at(cell), f"pasted at {cell}")
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

    def _fill(self, editor: Editor, mode: Mode, cell: Point) -> str:
        drawn = _drawn(editor, mode)
        region = shapes.flood_filled(drawn, cell)
        for seed in self._mirrored([cell])[1:]:  # the mirror's images fill their own regions
            if seed not in drawn and seed not in region:
                region = shapes.merged(region, shapes.flood_filled(drawn, seed))
        return _set(editor, mode, shapes.merged(drawn, region), f"filled {len(region)} cells at {cell}")

    # ------------------------------------------------------------------ drags
    def stroke_begin(self, editor: Editor, mode: Mode, cell: Point, erase: bool) -> str:
        """A drag with the cell tool (paint; ``erase``: the eraser) begins at ``cell``: one Undo takes
        back the whole stroke."""
        editor.begin_gesture()
        self._stroke = (erase, cell)
        return self._paint(editor, mode, [cell], erase, f"{'erasing' if erase else 'painting'} from {cell}")

    def stroke_to(self, editor: Editor, mode: Mode, cell: Point) -> str:
        """The drag moved on to ``cell``: every cell of the line from the last one is painted (a fast
        pointer skips cells between two reports)."""
        if self._stroke is None:
            return "no stroke in progress"
        erase, last = self._stroke
        self._stroke = (erase, cell)
        if cell == last:
            return ""
        return self._paint(editor, mode, shapes.line(last, cell), erase, f"stroke to {cell}")

    def stroke_end(self, editor: Editor) -> None:
        """The drag ends: all it painted or erased is one step of the history."""
        self._stroke = None
        editor.end_gesture()

    def _paint(self, editor: Editor, mode: Mode, cells: list[Point], erase: bool, what: str) -> str:
        cells = self._mirrored(cells)
        drawn = _drawn(editor, mode)
        changed = shapes.removed(drawn, cells) if erase else shapes.merged(drawn, cells)
        return _set(editor, mode, changed, what)

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
        """A dragged box: filled, or (``erase``) emptied; with the select tool, its cells selected."""
        if self.tool == "select":
            return self.selection.select(_drawn(editor, mode), a, b)
        what = f"{'erased' if erase else 'filled'} {a}–{b}"
        return self._paint(editor, mode, shapes.box(a, b), erase, what)

    def selection_command(self, editor: Editor, mode: Mode, name: str) -> str:
        """Copy, Cut, Delete or Deselect the selected cells."""
        chosen = self.selection
        if name == "Deselect":
            chosen.clear()
            return "nothing selected"
        if name not in ("Copy", "Cut", "Delete"):
            raise shapes.ShapeError(f"no selection command {name[:20]!r}")
        if not chosen.cells:
            return "nothing selected: choose the select tool and drag a box"
        said = chosen.copy() if name in ("Copy", "Cut") else ""
        if name == "Copy":
            return said
        gone = _set(editor, mode, shapes.removed(_drawn(editor, mode), chosen.cells), f"{name.lower()}")
        count = len(chosen.cells)
        chosen.clear()
        return f"{gone}: {count} cell(s)" + (f"; {said}" if said else "")

    def transform(self, editor: Editor, mode: Mode, name: str) -> str:
        """Mirror, rotate, scale the whole draft being edited; fit the pattern to the robots (cells added,
        never one removed) or the robots to the pattern (robots added or removed, the start kept solvable)."""
        cells = editor.robots if mode == "edit-robots" else editor.pattern
        if name == FIT_PATTERN:
            k = len(editor.robots)
            fitted, said = shapes.fitted(editor.pattern, k)  # cells added, or the last drawn trimmed
            return editor.set_pattern(fitted, f"the pattern fitted to {k} robots: {said}")
        if name == FIT_ROBOTS:
            n = len(editor.pattern)
            caution = self._caution_before(name, len(editor.robots), n)
            if caution:
                return caution
            robots, said = shapes.robots_fitted(editor.robots, n, lambda r: unsolvable_axis(r) is None)
            return editor.set_robots(robots, f"the robots fitted to the {n}-cell pattern: {said}")
        if name in NUDGES:
            dx, dy = NUDGES[name]
            chosen = self.selection
            if chosen.cells:  # the selection moves, the rest stays
                rest = shapes.removed(cells, chosen.cells)
                moved = shapes.merged(rest, shapes.translated(chosen.cells, dx, dy))
                chosen.moved(dx, dy)
                return _set(editor, mode, moved, f"moved the selection {name}")
            return _set(editor, mode, shapes.translated(cells, dx, dy), f"moved {name}")
        changed: dict[str, Callable[[Sequence[Point]], shapes.Cells]] = {
            "Mirror ↔": lambda c: shapes.mirrored(c, "x"),
            "Mirror ↕": lambda c: shapes.mirrored(c, "y"),
            "Rotate 90°": shapes.rotated,
            "Scale ×2": lambda c: shapes.scaled(c, 2),
        }
        if name not in changed:
            raise shapes.ShapeError(f"no transform {name[:40]!r}; transforms: {', '.join(TRANSFORMS)}")
        self.selection.clear()  # the cells it held moved
        return _set(editor, mode, changed[name](cells), name.lower())

    def _caution_before(self, name: str, have: int, want: int) -> str | None:
        """A fit that will take seconds is said first; the same fit asked again goes on."""
        if want - have <= CAUTION_CELLS or self._caution == (name, have, want):
            self._caution = None
            return None
        self._caution = (name, have, want)
        return (
            f"{name} will place {want - have:,} robots, each keeping the start solvable: that takes "
            f"seconds (about {max(1, (want - have) // 300)} s). Click {name} again to go on."
        )

    def fit_preview(self, editor: Editor) -> str:
        """What each fit would do to the drafts now, before it is clicked."""
        k, n = len(editor.robots), len(editor.pattern)
        if k == n:
            return f"{n} cells for {k} robots: nothing to fit"
        pattern = f"adds {k - n} cells" if k > n else f"trims the {n - k} last-drawn cells"
        robots = f"adds {n - k} robots" if n > k else f"removes the {k - n} last-placed robots"
        slow = " (seconds)" if n - k > CAUTION_CELLS else ""
        return f"Fit pattern {pattern} · Fit robots {robots}{slow}"

    def _add(self, editor: Editor, mode: Mode, cells: list[Point], what: str) -> str:
        return self._paint(editor, mode, cells, False, what)

    @staticmethod
    def _move(editor: Editor, mode: Mode, first: Point, to: Point) -> str:
        if mode == "edit-robots":
            return editor.move_robot(first, to)
        dx, dy = to[0] - first[0], to[1] - first[1]
        return editor.set_pattern(
            shapes.translated(editor.pattern, dx, dy), f"moved the pattern by ({dx}, {dy})"
        )


def _drawn(editor: Editor, mode: Mode) -> list[Point]:
    """The draft being edited: the robots in Edit robots, the pattern in Edit pattern."""
    return editor.robots if mode == "edit-robots" else editor.pattern


def _set(editor: Editor, mode: Mode, cells: list[Point], what: str) -> str:
    if mode == "edit-robots":
        return editor.set_robots(cells, what)
    return editor.set_pattern(cells, what)


def _noun(mode: Mode) -> str:
    return "robot" if mode == "edit-robots" else "target"
