"""Commands on the drafts: clicks, the modes, the pattern studio's tools."""

from __future__ import annotations

import numpy as np

from apf_viz.core import shapes
from apf_viz.core.formats import InputError
from apf_viz.core.grid import COORD_LIMIT, Point, short_int
from apf_viz.core.schedulers import BY_HAND
from apf_viz.workbench.library import PatternLibrary
from apf_viz.workbench.screen_state import BrowserState, Mode
from apf_viz.workbench.session.core import SessionCore
from apf_viz.workbench.studio import PAINTING
from apf_viz.workbench.studio import Mode as EditMode


class EditCommands(SessionCore):
    """Commands on the drafts: clicks, the modes, the pattern studio's tools."""

    # ------------------------------------------------------------------ clicks
    def robot_at(self, cell: Point) -> int | None:
        """The robot standing on ``cell`` now, or None."""
        hits = np.flatnonzero((self.engine.positions == np.array(cell)).all(axis=1))
        return int(hits[0]) if hits.size else None

    def click(self, cell: Point, state: BrowserState | None = None, drives: bool = True) -> str:
        """A click on a grid cell by one page (``state``: its state; the presenter's for None), which
        ``drives`` the run or only follows it, interpreted by the current mode: in Run it selects the
        robot there for that page (and in Manual, if it drives, runs its next phase). Returns what
        happened; a click outside the supported grid is refused (InputError)."""
        with self.lock:
            _on_grid(cell)
            if self.mode != "run":
                if not drives:
                    raise InputError("the presenter is drawing: a class page follows the drawing")
                studio = self.screen.studio
                studio.said = studio.click(self.editor, self.mode, cell)
                return studio.said
            r = self.robot_at(cell)
            state = state or self.presenter
            if r is None:
                state.selected = None
                return "nothing here"
            state.selected = r
            state.follow = False  # a robot of its own: the page no longer shows the presenter's
            if self.scheduler_name in BY_HAND and self.click_advances and not self.engine.finished and drives:
                return f"robot {r}: {self.run.step_robot(r)}"
            return f"selected robot {r}"

    def set_click_advances(self, advances: bool) -> None:
        """Manual: whether a click on a robot runs its next phase (advance) or only selects it, so that
        a student can read a robot's snapshot before choosing who acts."""
        with self.lock:
            self.screen.click_advances = bool(advances)

    # ------------------------------------------------------------------ editing
    def set_mode(self, mode: Mode) -> str | None:
        """Switch modes. Leaving an edit mode validates the drafts and restarts the run; on a problem the
        mode stays, the drafts are kept, and the problem is returned (for the browser that asked)."""
        with self.lock:
            if mode == self.mode:
                return None
            if self.mode != "run" and mode == "run":
                problem = self.editor.problem()
                if problem:
                    return problem
                e = self.editor
                self._start(
                    self.config.but(robots=tuple(e.robots), y_up=tuple(e.y_up), pattern=tuple(e.pattern))
                )
                return None
            self.run.pause()
            if mode == "edit-pattern":
                self._place_draft_beside_robots()
            self.mode = mode
            self.screen.studio.selection.clear()  # a selection is of one draft
            self.screen.studio.said = ""  # the last edit's words were of the mode left
            return None

    def _place_draft_beside_robots(self) -> None:
        """Move the drawn pattern beside the robots (a pattern is a shape: where it is drawn does not
        matter), where the run shows it before a leader places it, so it is framed with them and never
        drawn over them."""
        e = self.editor
        if not e.pattern or not e.robots:
            return
        dx = max(x for x, _ in e.robots) + 3 - min(x for x, _ in e.pattern)
        dy = min(y for _, y in e.robots) - min(y for _, y in e.pattern)
        if dx or dy:
            e.pattern = shapes.translated(e.pattern, dx, dy)

    def clear_pattern(self) -> None:
        """Remove every target being drawn (one Undo brings them back)."""
        with self.lock:
            self.editor.clear_pattern()

    def use_library(self, library: PatternLibrary) -> None:
        """Save and load patterns in ``library`` from now on (``serve --library``)."""
        with self.lock:
            self.library, self.saved = library, library.names()

    def save_pattern(self, name: str) -> str:
        """The pattern the page shows saved under ``name`` in the library: the one being drawn in either
        Edit mode (the robots' mode shows and counts it too), the run's in Run."""
        with self.lock:
            cells = self.editor.pattern if self.mode != "run" else list(self.config.pattern)
            path = self.library.save(name, cells)
            self.saved = self.library.names()
            self.name_pattern(cells, name)
            return f"saved {len(cells)} cells as {name.strip()!r} ({path})"

    def load_saved_pattern(self, name: str) -> str:
        """A saved pattern becomes the pattern being drawn (Edit pattern), beside the robots."""
        cells = self.library.load(name)
        with self.lock:
            self.name_pattern(cells, name)
            self.run.pause()
            said = self.editor.set_pattern(
                cells, f"loaded {name!r}: {len(cells)} cells for {self.engine.k} robots"
            )
            self.mode = "edit-pattern"
            self._place_draft_beside_robots()
            return said

    # ------------------------------------------------------------------ the pattern studio
    def set_tool(self, tool: str) -> None:
        """The studio's tool for the next gestures (an unknown one is refused)."""
        with self.lock:
            self.screen.studio.choose(tool)

    def set_tool_size(self, size: float) -> None:
        """The size of a placed shape (a ring's radius, a row's length): a whole number 1 .. 200."""
        if (
            not isinstance(size, int | float)
            or size != size
            or not float(size).is_integer()
            or not 1 <= size <= 200
        ):
            raise InputError(f"size {size!r}: choose a whole number from 1 to 200")
        with self.lock:
            self.screen.studio.size = int(size)

    def set_tool_text(self, text: str) -> None:
        """The text tool's word (refused before anything changes if the font lacks a character)."""
        shapes.text(text, (0, 0))  # refuses a character the font has not, before anything changes
        with self.lock:
            self.screen.studio.text = text

    def draw_box(self, a: Point, b: Point, erase: bool) -> str:
        """A box dragged in an edit mode: filled, or (``erase``) emptied."""
        with self.lock:
            for cell in (a, b):
                _on_grid(cell)
            if self.mode == "run":
                return "drag a box in Edit pattern or Edit robots"
            return self.screen.studio.box(self.editor, self.mode, a, b, erase)

    def set_mirror(self, which: str) -> str:
        """The live mirror: off, x ↔, y ↕ or both, about the middle of the draft being edited."""
        with self.lock:
            mode: EditMode = "edit-robots" if self.mode == "edit-robots" else "edit-pattern"
            return self.screen.studio.set_mirror(self.editor, mode, which)

    def stroke(self, phase: str, cell: Point | None) -> str:
        """A drag on the canvas with the cell tool or the eraser: ``phase`` start, update or end (the
        cell under the pointer; None where it is off the grid)."""
        with self.lock:
            studio = self.screen.studio
            if phase == "end" or self.mode == "run" or studio.tool not in PAINTING:
                studio.stroke_end(self.editor)
                return ""
            if cell is None:
                return ""
            _on_grid(cell)
            if phase == "start":
                studio.said = studio.stroke_begin(self.editor, self.mode, cell, studio.tool == "eraser")
            else:
                studio.said = studio.stroke_to(self.editor, self.mode, cell) or studio.said
            return studio.said

    def selection_command(self, name: str) -> str:
        """Copy, Cut, Delete or Deselect the studio's selection."""
        with self.lock:
            if self.mode == "run":
                return "select cells in Edit pattern or Edit robots"
            return self.screen.studio.selection_command(self.editor, self.mode, name)

    def transform(self, name: str) -> str:
        """Mirror, rotate, scale or fit the draft being edited; Undo and Redo."""
        with self.lock:
            if self.mode == "run":
                return "transforms change a draft: choose Edit pattern or Edit robots"
            if name == "Undo":
                return self.editor.undo()
            if name == "Redo":
                return self.editor.redo()
            return self.screen.studio.transform(self.editor, self.mode, name)


def _on_grid(cell: Point) -> None:
    """Refuse a cell outside the grid this tool supports (a browser may send any point)."""
    if abs(cell[0]) > COORD_LIMIT or abs(cell[1]) > COORD_LIMIT:
        raise InputError(
            f"({short_int(cell[0])}, {short_int(cell[1])}) is outside the grid this tool supports "
            f"(|x|, |y| ≤ {COORD_LIMIT:,})"
        )
