"""The grid: its lines as two line sets, as dense as a reader can use."""

from __future__ import annotations

import numpy as np

from apf_viz.ui.scene.canvas import Canvas
from apf_viz.ui.scene.style import GRID_CELL_PX, GRID_SECTION_PX, SECTION_STEPS, VIEW_PX


def grid_steps(width: int) -> tuple[bool, int]:
    """(whether every cell gets a line, the step of the section lines) for a grid ``width`` cells wide.

    Lines no denser than a reader can use, which also bounds their number: each line is an instance, and
    a software-rendered browser spends about 0.2 ms a frame on each (docs/PERFORMANCE.md)."""
    px = VIEW_PX / max(width, 1)
    section = next((s for s in SECTION_STEPS if s * px >= GRID_SECTION_PX), SECTION_STEPS[-1])
    return px >= GRID_CELL_PX, section


class GridLayer(Canvas):
    """Draws the grid under the run."""

    def _grid(self) -> None:
        x0, y0, x1, y1 = self.bounds
        key = (int(np.floor(x0)) - 6, int(np.floor(y0)) - 6, int(np.ceil(x1)) + 6, int(np.ceil(y1)) + 6)
        old = self._grid_key
        if (
            old is not None
            and all(a <= b for a, b in zip(old[:2], key[:2], strict=True))
            and all(a >= b for a, b in zip(old[2:], key[2:], strict=True))
            # A run (or drawing) that shrank far inside the grid drawn gets its own again: a grid laid out
            # for a far cell since erased would keep no line per cell.
            and max(old[2] - old[0], old[3] - old[1]) <= 2 * max(key[2] - key[0], key[3] - key[1]) + 24
        ):
            return
        key = (key[0] - 6, key[1] - 6, key[2] + 6, key[3] + 6)  # grow with room to spare
        self._grid_key = key
        # Grid lines pass through integer points: robots sit on the lattice points. Two line sets in
        # screen pixels, not viser's grid plane: its shader over the whole plane cost a software-rendered
        # browser more than everything else in the scene together (docs/PERFORMANCE.md).
        x0, y0, x1, y1 = key
        cells, section = grid_steps(max(x1 - x0, y1 - y0))
        for name, step, color, width in (
            ("/grid/cells", 1, (205, 205, 205), 1.0),
            ("/grid/sections", section, (175, 175, 175), 1.5),
        ):
            if step == 1 and not cells:
                self._segments(name, np.zeros((0, 2, 3), np.float32), color, width)
                continue
            xs = np.arange(x0 - x0 % step, x1 + 1, step, dtype=np.float32)
            ys = np.arange(y0 - y0 % step, y1 + 1, step, dtype=np.float32)
            if step == 1:  # the section lines are drawn once, by the other set
                xs, ys = xs[xs % section != 0], ys[ys % section != 0]
            vertical = np.stack(
                [np.column_stack([xs, np.full_like(xs, y0)]), np.column_stack([xs, np.full_like(xs, y1)])], 1
            )
            horizontal = np.stack(
                [np.column_stack([np.full_like(ys, x0), ys]), np.column_stack([np.full_like(ys, x1), ys])], 1
            )
            flat = np.concatenate([vertical, horizontal])
            segments = np.concatenate([flat, np.full((len(flat), 2, 1), -0.01, np.float32)], axis=2)
            self._segments(name, segments, color, width)
