"""What the algorithm describes over the run: target cells, its lines and frames, pending moves."""

from __future__ import annotations

import numpy as np

from apf_viz.core.portrayal import Cells, Frame, Line
from apf_viz.ui.scene.canvas import Canvas
from apf_viz.ui.scene.labels import cells_label_at, frame_label_at, label_box, line_label_at
from apf_viz.ui.scene.style import Z, xyz
from apf_viz.workbench.palette import MARK_COLORS, TARGET_COLORS
from apf_viz.workbench.view_model import SessionView


class MarksLayer(Canvas):
    """Draws the algorithm's marks (core/portrayal.py) and the pending moves."""

    # ------------------------------------------------------------------ the algorithm's marks
    def _targets(self, view: SessionView) -> None:
        """The first set of cells the algorithm gives (where the pattern forms), or the pattern drawn."""
        cells = next((m for m in view.overlays.marks if isinstance(m, Cells)), None)
        style = cells.style if cells else "placed"  # the legend shows the same swatch
        points = self._local(cells.points if cells else ())
        self._points("/targets", xyz(points, 0.005), TARGET_COLORS[style], 0.8)

    def _marks(self, view: SessionView, robots: np.ndarray, taken: list | None = None) -> list:
        """Lines and frames of the overlays, each labelled on the canvas (``robots``: their scene points; a
        label goes where none is, nor a label already there: ``taken``, the robots' own). A handful per
        run: a node each, created once per slot and updated in place. Returns ``taken`` and the boxes of
        the labels placed here."""
        lines = [m for m in view.overlays.marks if isinstance(m, Line)]
        frames = [m for m in view.overlays.marks if isinstance(m, Frame)]
        labels: list[tuple[str, tuple[float, float, float]]] = []
        height = self._text_height()
        taken = list(taken or [])
        for i in range(max(len(lines), self._slots.get("line", 0))):
            mark = lines[i] if i < len(lines) else None
            segs = self._line(mark) if mark else np.zeros((0, 2, 3), np.float32)
            color = (mark.color if mark else None) or MARK_COLORS["line"]
            self._segments(f"/marks/line{i}", segs, color, 3.0)
            if mark:
                end = (float(segs[0, 1, 0]), float(segs[0, 1, 1]))
                spot = line_label_at(end, robots, mark.label, height, taken)
                labels.append((mark.label, spot))
                taken.append(label_box(mark.label, (spot[0], spot[1], spot[0]), height))
        self._slots["line"] = max(len(lines), self._slots.get("line", 0))
        # the cells' label next: a frame's label has more places to go
        cells = next((m for m in view.overlays.marks if isinstance(m, Cells)), None)
        if cells is not None and cells.points and view.mode != "edit-pattern":
            local = self._local(cells.points)
            spot = cells_label_at(local, robots, cells.label, height, taken)
            labels.append((cells.label, spot))
            taken.append(label_box(cells.label, (spot[0], spot[1], spot[0]), height))
        for i in range(max(len(frames), self._slots.get("frame", 0))):
            frame = frames[i] if i < len(frames) else None
            segs = self._frame(frame) if frame else np.zeros((0, 2, 3), np.float32)
            self._segments(
                f"/marks/frame{i}", segs, (frame.color if frame else None) or MARK_COLORS["frame"], 3.0
            )
            if frame:
                origin = (float(segs[0, 0, 0]), float(segs[0, 0, 1]))
                spot = frame_label_at(origin, frame.y_sign, robots, frame.label, height, taken)
                labels.append((frame.label, spot))
                taken.append(label_box(frame.label, (spot[0], spot[1], spot[0]), height))
        self._slots["frame"] = max(len(frames), self._slots.get("frame", 0))
        self._labels("/marks/labels", labels)
        return taken  # every label's box: those given, then the cells' and the frames'

    def _frame(self, mark: Frame) -> np.ndarray:
        ox, oy = self.to_scene(mark.origin)
        s = mark.y_sign
        z = 0.08
        return np.array(
            [
                [(ox, oy, z), (ox + 2, oy, z)],
                [(ox + 2, oy, z), (ox + 1.7, oy + 0.2, z)],
                [(ox, oy, z), (ox, oy + 2 * s, z)],
                [(ox, oy + 2 * s, z), (ox + 0.2, oy + 1.7 * s, z)],
            ],
            dtype=np.float32,
        )

    def _pending(self, view: SessionView) -> np.ndarray:
        pairs = [(r.position, r.pending) for r in view.robots if r.pending is not None]
        ends = self._local(np.array(pairs, dtype=np.int64).reshape(-1, 2)).reshape(-1, 2, 2)
        return np.concatenate([ends, np.full((len(ends), 2, 1), Z + 0.04, dtype=np.float32)], axis=2)
