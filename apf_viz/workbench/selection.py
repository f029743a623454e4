"""The studio's rectangular selection and its clipboard: which drawn cells a dragged box took, and what
Copy or Cut kept for Paste. The drafts themselves change through the editor (workbench/editor.py)."""

from __future__ import annotations

from apf_viz.core import shapes
from apf_viz.core.grid import Point

SELECTION_COMMANDS = ("Copy", "Cut", "Delete", "Deselect")


class Selection:
    """The cells a box selected (in the draft being edited), and the clipboard (cells from its
    bottom-left corner, (0, 0))."""

    def __init__(self) -> None:
        self.cells: tuple[Point, ...] = ()
        self.box: tuple[Point, Point] | None = None
        self.clipboard: tuple[Point, ...] = ()

    def select(self, drawn: list[Point], a: Point, b: Point) -> str:
        """Select the drawn cells in the box from ``a`` to ``b``; returns what was selected, in words."""
        self.cells = tuple(shapes.inside(drawn, a, b))
        self.box = (a, b) if self.cells else None
        if not self.cells:
            return f"nothing drawn in {a}–{b}: nothing selected"
        return f"selected {len(self.cells)} cell(s) in {a}–{b}: Copy, Cut, Delete, or Move all moves them"

    def clear(self) -> None:
        """Select nothing (the clipboard is kept)."""
        self.cells, self.box = (), None

    def box_over(self, drawn: list[Point]) -> tuple[Point, Point] | None:
        """The box outlined: while some cell it selected is still drawn (after an erase, an Undo or a
        clear that took them all, an outline would describe nothing)."""
        if self.box is None:
            return None
        here = set(drawn)
        return self.box if any(c in here for c in self.cells) else None

    def copy(self) -> str:
        """Keep the selected cells on the clipboard, from their bottom-left corner; returns what was copied,
        in words."""
        if not self.cells:
            return "nothing selected: choose the select tool and drag a box"
        x0, y0 = min(x for x, _ in self.cells), min(y for _, y in self.cells)
        self.clipboard = tuple((x - x0, y - y0) for x, y in self.cells)
        return f"copied {len(self.clipboard)} cell(s): the paste tool places them where you click"

    def pasted_at(self, cell: Point) -> list[Point]:
        """The clipboard with its bottom-left corner at ``cell``."""
        return [(x + cell[0], y + cell[1]) for x, y in self.clipboard]

    def moved(self, dx: int, dy: int) -> None:
        """The selection follows its cells when Move all moves them."""
        self.cells = tuple(shapes.translated(self.cells, dx, dy))
        if self.box is not None:
            (xa, ya), (xb, yb) = self.box
            self.box = ((xa + dx, ya + dy), (xb + dx, yb + dy))
