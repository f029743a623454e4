"""The surface a drag paints on: while the cell tool or the eraser is chosen in an edit mode, one
browser's scene holds an invisible plane under the grid whose drags viser reports (start, update about
20 times a second, end), and the camera stays still under the drag. Otherwise the plane is gone and a
drag turns the camera, as everywhere else."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from apf_viz.ui.scene.style import FULL_CANVAS_MATERIAL

PLANE_SIDE = 1e6  # cells: wider than any canvas shows
NAME = "/paint-surface"

Stroke = Callable[[object, str, "tuple[float, float] | None"], None]


class PaintSurface:
    """One browser's paint surface: shown or not, and where its drags go (``on_stroke(client, phase,
    screen point)``, the point 0..1 each way from the canvas's top-left)."""

    def __init__(self, client, on_stroke: Stroke) -> None:
        self._client = client
        self._on_stroke = on_stroke
        self._plane: Any = None  # viser's box handle while shown

    def show(self, wanted: bool) -> None:
        if wanted == (self._plane is not None):
            return
        if not wanted:
            self._plane.remove()
            self._plane = None
            return
        plane = self._client.scene.add_box(
            NAME,
            color=(255, 255, 255),
            dimensions=(PLANE_SIDE, PLANE_SIDE, 0.001),
            opacity=0.0,
            material=FULL_CANVAS_MATERIAL,  # the plane fills the canvas: no lit pass over every pixel
            cast_shadow=False,
            receive_shadow=False,
            position=(0.0, 0.0, -0.05),
        )
        plane.on_drag(self._dragged)
        self._plane = plane

    def _dragged(self, event) -> None:
        self._on_stroke(event.client, event.phase, tuple(event.end_screen_pos))
