"""The drawing primitives every layer of the scene shares, and the state they keep."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from apf_viz.core.portrayal import Frame, Line
from apf_viz.ui.scene.camera import cell_of_ray, point_of_ray, pose_for
from apf_viz.ui.scene.labels import text_cells
from apf_viz.ui.scene.style import LABEL_SCALE, REORIGIN_DISTANCE, VISER_POINT_SCALE, Bounds
from apf_viz.workbench.palette import PointShape
from apf_viz.workbench.view_model import SessionView
from apf_viz.workbench.view_model.legend import canvas_symbol


class Canvas:
    """What every part of the scene draws with: nodes created once and updated in place (points,
    segments, labels), the integer origin the float32 scene is drawn around, and the run's box."""

    def __init__(self, owner, prefix: str = "", root: str = "") -> None:
        self.server = owner
        # A second run drawn beside the first (Compare) is a second renderer under its own prefix, its
        # origin set by the caller so that it stands to the right of the first.
        self.prefix = prefix
        # Every node is drawn under ``root`` (a frame): one browser can hide a whole scope at once (a
        # page trying a run of its own hides the shared run under a frame of its own of the same name).
        self.root = root
        self.fixed_origin: tuple[int, int] | None = None
        self.scene = owner.scene
        self._sprite_lights: set[tuple[str, bool]] = set()  # (light, drawn square) of every robot cloud
        self._ghost_lights: set[str] = set()
        self._trail_lights: set[str] = set()
        self._colors: dict[str, tuple[int, int, int]] = {}  # each point cloud's colour
        self._counts: dict[str, int] = {}
        self._last: dict[str, tuple] = {}  # what each node shows now, to send only changes
        self._handles: dict[str, object] = {}
        self.bounds: Bounds = (0, 0, 1, 1)  # scene units: grid minus origin
        self.origin: tuple[int, int] = (0, 0)  # the grid point drawn at the scene's (0, 0)
        self._grid_key: tuple[int, int, int, int] | None = None
        self._slots: dict[str, int] = {}  # nodes made so far per kind of mark (reused, hidden when idle)
        self.framed_pose = pose_for(self.bounds)  # the pose browsers were last sent (tests project with it)
        # How many cells tall the view of the browser zoomed in furthest is (the app sets it from the
        # cameras); None: the framed pose's.
        self.view_cells: float | None = None
        # A label's height in cells on the page that shows labels largest (cells per pixel: the most of
        # the framed pages'), set by the app; None: laid out for the framed pose.
        self.text_height: float | None = None
        self.label_boxes: list[Bounds] = []  # where the last frame's labels are (SceneRenderer.render)

    # ------------------------------------------------------------------ what others may ask
    def nodes(self) -> dict[str, object]:
        """Every node this canvas has drawn, by name (hidden ones included: a handle's ``visible``)."""
        return dict(self._handles)

    def words(self, prefix: str, placed: list) -> None:
        """Lines of text at scene positions (``(text, (x, y, z))``), under ``prefix``: an exported page's
        words beside its run (ui/page_export.py)."""
        self._labels(prefix, placed)

    def visible_height(self) -> float:
        """How many cells tall the framed view is (the initial camera's pose: what browsers are framed
        to, near enough for laying out labels)."""
        position, look_at, fov = self.framed_pose
        return 2.0 * abs(position[2] - look_at[2]) * float(np.tan(fov / 2))

    # ------------------------------------------------------------------ batched helpers
    def _text_height(self) -> float:
        """A label's height in cells, for laying labels out where each page framed on the run shows them
        apart: boxes apart at the largest size stay apart at every smaller one."""
        if self.text_height is not None:
            return self.text_height
        return text_cells(self.view_cells if self.view_cells is not None else self.visible_height())

    def _in_place(self, name: str, data: np.ndarray, create: Callable[[], object], field: str) -> None:
        """Send ``data`` to the node ``name`` only if it changed: create the node once, then assign
        ``field`` in place; hide it when empty. (A node removed and re-added gets a new material, and
        the browser compiles its shader again: in a software-rendered browser that costs a frame.)"""
        last = self._last.get(name)
        if last is not None and np.array_equal(last[0], data):
            return
        self._last[name] = (data, None, None)
        handle = self._handles.get(name)
        if not len(data):
            if handle is not None:
                handle.visible = False  # type: ignore[attr-defined]
            return
        if handle is None:
            self._handles[name] = create()
        else:
            setattr(handle, field, data)
            handle.visible = True  # type: ignore[attr-defined]

    def _points(
        self,
        name: str,
        points: np.ndarray,
        color: tuple[int, int, int],
        size: float,
        shape: PointShape = "square",
    ) -> None:
        """Points of one colour and size (world units), flat and unlit: squares (target cells), discs
        (robots, rings) or diamonds."""
        self._in_place(
            name,
            points,
            lambda: self.scene.add_point_cloud(
                self.root + self.prefix + name,
                points,
                np.array(color, dtype=np.uint8),
                point_size=size * VISER_POINT_SCALE,
                point_shape=shape,
                precision="float32",
                point_shading="flat",
            ),
            "points",
        )
        handle = self._handles.get(name)
        if handle is not None and self._colors.get(name, color) != color:  # rare: e.g. a mode switch
            handle.colors = np.array(color, dtype=np.uint8)  # type: ignore[attr-defined]
        self._colors[name] = color

    def _segments(
        self,
        name: str,
        segments: np.ndarray,
        color: tuple[int, int, int],
        thickness: float,
    ) -> None:
        """Line segments, shape (n, 2, 3), ``thickness`` pixels wide."""
        points = segments.astype(np.float32)
        self._in_place(
            name,
            points,
            lambda: self.scene.add_line_segments(
                self.root + self.prefix + name, points, color, thickness=thickness, thickness_units="screen"
            ),
            "points",
        )

    def _labels(self, prefix: str, labels: list) -> None:
        """Text on the canvas, one node per slot, updated in place (text, position, anchor) and hidden
        when unused. A label is (text, position) or (text, position, anchor): its lower left by default,
        its lower right or middle for one laid out on the left of a robot or above it (labels.spread)."""
        key = tuple(labels)
        if self._last.get(prefix) == (key, None, None):
            return
        self._last[prefix] = (key, None, None)
        used = self._slots.get(prefix, 0)
        for i in range(max(used, len(labels))):
            name = f"{prefix}/{i}"
            handle = self._handles.get(name)
            if i < len(labels):
                text, position, *rest = labels[i]
                anchor = rest[0] if rest else "bottom-left"
                text = canvas_symbol(text)
                if handle is None:
                    self._handles[name] = self.scene.add_label(
                        self.root + self.prefix + name,
                        text,
                        position=position,
                        font_screen_scale=LABEL_SCALE,
                        anchor=anchor,
                    )
                else:
                    handle.text = text  # type: ignore[attr-defined]
                    handle.position = position  # type: ignore[attr-defined]
                    if handle.anchor != anchor:  # type: ignore[attr-defined]
                        handle.anchor = anchor  # type: ignore[attr-defined]
                    handle.visible = True  # type: ignore[attr-defined]
            elif handle is not None:
                handle.visible = False  # type: ignore[attr-defined]
        self._slots[prefix] = max(used, len(labels))

    def clear(self) -> None:
        """Remove everything this renderer drew (Compare stopped)."""
        for handle in self._handles.values():
            handle.remove()  # type: ignore[attr-defined]
        self._handles.clear()
        self._last.clear()
        self._counts.clear()
        self._slots.clear()
        self._colors.clear()
        self._sprite_lights.clear()
        self._ghost_lights.clear()
        self._trail_lights.clear()
        self._grid_key = None

    # ------------------------------------------------------------------ origin
    def _place_origin(self, robots: np.ndarray, view: SessionView) -> None:
        """Keep the origin near the run (robots and targets, grid coordinates)."""
        if self.fixed_origin is not None:
            if self.fixed_origin != self.origin:
                self.origin = self.fixed_origin
                self._grid_key = None
            return
        allp = np.vstack([robots, np.array(view.targets, dtype=np.int64).reshape(-1, 2)])
        if not len(allp):
            return
        lo, hi = allp.min(axis=0).tolist(), allp.max(axis=0).tolist()
        ox, oy = self.origin
        if max(abs(lo[0] - ox), abs(hi[0] - ox), abs(lo[1] - oy), abs(hi[1] - oy)) > REORIGIN_DISTANCE:
            self.origin = ((lo[0] + hi[0]) // 2, (lo[1] + hi[1]) // 2)
            self._grid_key = None  # the grid is drawn anew around the new origin

    def _local(self, points) -> np.ndarray:
        """Grid points as scene points, shape (n, 2) float32: minus the origin, in exact integers first."""
        arr = np.asarray(points, dtype=np.int64).reshape(-1, 2)
        return (arr - np.array(self.origin, dtype=np.int64)).astype(np.float32)

    def to_scene(self, cell: tuple[int, int]) -> tuple[float, float]:
        """Where a grid point is drawn (for tests and the camera)."""
        return float(cell[0] - self.origin[0]), float(cell[1] - self.origin[1])

    def cell_of_ray(self, origin, direction) -> tuple[int, int] | None:
        """The grid cell a click ray hits (see :func:`cell_of_ray`), in grid coordinates."""
        cell = cell_of_ray(origin, direction)
        return None if cell is None else (cell[0] + self.origin[0], cell[1] + self.origin[1])

    def point_of_ray(self, origin, direction) -> tuple[float, float] | None:
        """Where a ray hits the grid, in grid coordinates (a cell's centre is its whole point)."""
        point = point_of_ray(origin, direction)
        return None if point is None else (point[0] + self.origin[0], point[1] + self.origin[1])

    def _update_bounds(self, pts: np.ndarray, view: SessionView) -> None:
        """The box the camera keeps in view: robots, targets, and the corners of the overlays' frames
        (a frame's arms reach two cells from its origin)."""
        corners = [
            (f.origin[0] + dx, f.origin[1] + f.y_sign * dy)
            for f in view.overlays.marks
            if isinstance(f, Frame)
            for dx, dy in ((0, 0), (2, 2))
        ]
        extra = self._local([*view.targets, *corners])
        allp = np.vstack([pts, extra]) if len(extra) else pts
        if len(allp) == 0:
            allp = np.zeros((1, 2), dtype=np.float32)
        lo, hi = allp.min(axis=0), allp.max(axis=0)
        self.bounds = (float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1]))

    def _line(self, mark: Line) -> np.ndarray:
        x0, y0, x1, y1 = self.bounds
        if mark.axis == "y":
            y = mark.at - self.origin[1]
            return np.array([[(x0 - 2, y, 0.05), (x1 + 2, y, 0.05)]], dtype=np.float32)
        x = mark.at - self.origin[0]
        return np.array([[(x, y0 - 2, 0.05), (x, y1 + 2, 0.05)]], dtype=np.float32)
