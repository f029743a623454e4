"""The only module that touches a viser scene: draws a :class:`SessionView`, one atomic update a frame;
the run in the scene every browser shares, each browser's selection in that browser's own scene.

Robots are flat, unlit discs in their light's legend colour (one point cloud per light) on a dark
outline (left out while a crowd framed whole plays: ``RIM_CROWD``), with a small diamond on each robot's
+y side for its y-axis (the adversary's flip); its phase, the last actor and the selection are rings:
wider discs under it. One vertex per robot and ring, because
in a browser without a GPU every instance of a batched mesh or line set costs about as much as a draw
call of its own. Up to ``DENSE`` robots a pending move is a line segment, above it a red dot on the cell
it goes to. Target cells are flat squares; rays, K, the leader's frame and the grid are line-segment
sets, the grid's density chosen by :func:`grid_steps`. Every node is created once and then updated in
place, hidden when empty: a node re-created gets a new material, and a software-rendered browser
compiles its shader again. docs/PERFORMANCE.md has the measurements.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Literal

import numpy as np

from apf_viz.core.portrayal import Band, Cells, Frame, HalfPlane, Line
from apf_viz.ui.palette import MARK_COLORS, MARK_SHAPES, PHASE_COLORS, TARGET_COLORS, PointShape, region_color
from apf_viz.ui.view_model import SessionView
from apf_viz.ui.view_model.legend import canvas_symbol

ROBOT_RADIUS = 0.3
# Grid density, for a run framed about VIEW_PX pixels wide: a line per cell while a cell is at least
# GRID_CELL_PX wide, and darker section lines every 5, 10, 50, ... cells, at least GRID_SECTION_PX apart.
VIEW_PX = 1000
GRID_CELL_PX = 20
GRID_SECTION_PX = 45
_SECTION_STEPS = (5, 10, 50, 100, 500, 1000, 5000, 10000)
# Above this many robots, robots, y-axes and pending moves are point sprites, one vertex each, not
# instanced meshes and line segments: in a software-rendered browser each instance costs about 0.2 ms a
# frame, as much as a draw call (measured, docs/PERFORMANCE.md).
DENSE = 50
# viser draws a point of size s as a square 2·s world units wide (its scale divides by tan(fov/2), where
# the frustum's height is 2·tan(fov/2)·z); sizes here are world widths.
_VISER_POINT_SCALE = 0.5
# Robots and their rings are flat discs in layers just above the grid, far enough apart for the depth
# buffer (about 0.006 units at a typical camera distance) and close enough that perspective does not
# shift one against another. Flat and unlit: a light's colour on the canvas is its legend swatch.
Bounds = tuple[float, float, float, float]  # (x0, y0, x1, y1) in scene units: a run's box, a label's
Z = 0.12  # the robots' discs
_LAYER = {
    "diverged": 0.015,  # Compare's diverging robot: a diamond under everything
    "anchor": 0.016,  # Edit: a two-click tool's first click, a diamond whose corners show round a robot
    "selected": 0.02,  # rings, widest at the bottom
    "never": 0.03,
    "last": 0.04,
    "phase": 0.06,
    "ghost_outline": 0.075,
    "ghost": 0.085,
    "outline": 0.1,
    "fog": 0.13,  # over a robot the selected one cannot see, and on the robot that hides it
    "nose": 0.14,
}
NOSE_CELLS = 0.16  # the y-axis diamond's width in cells
NOSE_MIN_PX = 2.5
"""Below this width on screen the y-axis diamonds are not drawn: a pixel-wide speck says nothing, and over
a 1,000-robot run framed whole they are a thousand points the page draws every frame (a tenth of a
software-rendered frame, docs/PERFORMANCE.md). Zoomed in, they are drawn again."""
RIM_CROWD = 500
RIM_PLAYING_PX = GRID_CELL_PX
"""While a run of at least ``RIM_CROWD`` robots plays, their dark outlines are drawn only where a cell is
at least this wide on screen (the width under which the grid has no line per cell either): over a
crowd framed whole they are a thousand more discs in every frame, a tenth of a software-rendered
page's frame at full resolution (docs/PERFORMANCE.md, 60be800), and a pixel-wide ring. Paused, or
zoomed in, they are drawn; a smaller run keeps them (its outlines cost the page little)."""
GHOST_BADGE_OFFSET = (-0.34, 0.34)  # a light-only ghost, beside the robot it is the ghost of
STALE_MARK = "stale"  # beside every robot holding a snapshot that others' moves or lights have made stale
_SIZE = {  # disc diameters in cells: each ring shows as the band between its disc and the next
    "selected": 1.22,
    "never": 1.1,
    "last": 1.02,
    "phase": 0.88,
    "outline": 2 * ROBOT_RADIUS + 0.1,
    "robot": 2 * ROBOT_RADIUS,
}


def grid_steps(width: int) -> tuple[bool, int]:
    """(whether every cell gets a line, the step of the section lines) for a grid ``width`` cells wide.

    Lines no denser than a reader can use, which also bounds their number: each line is an instance, and
    a software-rendered browser spends about 0.2 ms a frame on each (docs/PERFORMANCE.md)."""
    px = VIEW_PX / max(width, 1)
    section = next((s for s in _SECTION_STEPS if s * px >= GRID_SECTION_PX), _SECTION_STEPS[-1])
    return px >= GRID_CELL_PX, section


def light_colors(view: SessionView) -> dict[str, tuple[int, int, int]]:
    """Each light's colour, from the algorithm's legend (core/portrayal.py gives every light one)."""
    return {light: style.color for light, style in view.legend.items()}


REGION_OPACITY = 0.13
# The canvas a new browser is framed for before it reports its own: 1024×768 with the panel docked
# (about 640×768). A wider canvas then shows a margin; a narrower guess would cut a 1024 projector's view.
NARROW_ASPECT = 0.83
LABEL_SCALE = 1.1


def number_labels(
    pts: list[list[float]], numbers: bool, stale: tuple[int, ...]
) -> list[tuple[str, tuple[float, float, float]]]:
    """Each robot's number at its upper right, "stale" joined to it for a robot holding a stale snapshot
    (one label per robot: it cannot be read as a neighbour's, nor pile onto another); without numbers,
    "stale" alone in the same place."""
    holding = set(stale)
    return [
        (
            f"{i} {STALE_MARK}" if numbers and i in holding else str(i) if numbers else STALE_MARK,
            (x + 0.25, y + 0.3, 0.7),
        )
        for i, (x, y) in enumerate(pts)
        if numbers or i in holding
    ]


def _xyz(points, z: float) -> np.ndarray:
    arr = np.asarray(points, dtype=np.float32).reshape(-1, 2)
    return np.column_stack([arr, np.full(len(arr), z, dtype=np.float32)])


# The browser draws in float32, exact for integers only below 2^24 and smooth only well below: the scene is
# drawn relative to an integer origin near the run, moved when the run is farther than this from it.
REORIGIN_DISTANCE = 1 << 20


Layer = Literal["all", "run", "selection"]


class SceneRenderer:
    """Draws session views into one scene: the server's (every browser) or one browser's.

    ``layer``: ``run`` draws what every browser shares (robots, rings, targets, the algorithm's marks);
    ``selection`` what belongs to one browser's selection (its ring, rays, ghosts, Why's regions), in
    that browser's own scene, placed by the ``base`` renderer's origin; ``all`` both (one browser)."""

    def __init__(
        self, owner, prefix: str = "", layer: Layer = "all", base: SceneRenderer | None = None
    ) -> None:
        self.server = owner
        # A second run drawn beside the first (Compare) is a second renderer under its own prefix, its
        # origin set by the caller so that it stands to the right of the first.
        self.prefix = prefix
        self.layer: Layer = layer
        self.base = base
        self.fixed_origin: tuple[int, int] | None = None
        self.scene = owner.scene
        if layer != "selection" and not prefix:
            # The scene's own settings, once: a second renderer in the same scene (Compare) setting the
            # up direction again makes every page reset its camera to the initial pose.
            self.scene.set_up_direction("+z")
            # Nothing here casts a shadow, but lights that may cast one make the browser clear three
            # 1024² shadow maps every frame: a tenth of a software-rendered frame (docs/PERFORMANCE.md).
            self.scene.configure_default_lights(enabled=True, cast_shadow=False)
        self._sprite_lights: set[str] = set()
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
        self.framed_pose = self.camera_pose()  # the pose browsers were last sent (tests project with it)
        # How many cells tall the view of the browser zoomed in furthest is (the app sets it from the
        # cameras); None: the framed pose's.
        self.view_cells: float | None = None

    # ------------------------------------------------------------------ batched helpers
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
                self.prefix + name,
                points,
                np.array(color, dtype=np.uint8),
                point_size=size * _VISER_POINT_SCALE,
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
                self.prefix + name, points, color, thickness=thickness, thickness_units="screen"
            ),
            "points",
        )

    # ------------------------------------------------------------------ drawing
    def render(self, view: SessionView, title: str | None = None) -> None:
        """Draw one frame; the caller wraps it in ``server.atomic()``. ``title``: a label above the run
        (Compare names each side)."""
        if self.layer == "selection":
            assert self.base is not None
            self.origin, self.bounds = self.base.origin, self.base.bounds
            self._selection(view)
            return
        editing_robots = view.mode == "edit-robots"
        grid_pts = np.array([r.position for r in view.robots], dtype=np.int64).reshape(-1, 2)
        self._place_origin(grid_pts, view)
        pts = self._local(grid_pts)
        self._update_bounds(pts, view)
        if title:  # Compare's titles stand above each run: keep them in view too
            x0, y0, x1, y1 = self.bounds
            self.bounds = (x0, y0, x1, y1 + 3.0)
        self._grid()
        dense = len(pts) > DENSE
        self._robots(view, pts)
        self._rings(view, pts)
        self._labels("/numbers", number_labels(pts.tolist(), view.numbers, view.stale_holders))
        split = pts[view.diverged : view.diverged + 1] if view.diverged is not None else pts[:0]
        self._points("/diverged", _xyz(split, _LAYER["diverged"]), MARK_COLORS["diverged"], 1.5, "diamond")
        here = [("diverges here", (float(x) + 0.45, float(y) - 0.2, 0.7)) for x, y in split.tolist()]
        self._labels("/diverged_label", here)
        crash = self._local(view.collision[1]) if view.collision else pts[:0]
        self._points(
            "/collision", _xyz(crash, 0.006), MARK_COLORS["collision"], 1.6, MARK_SHAPES["collision"]
        )
        self._targets(view)
        self._trails(view)
        # Line widths in screen pixels: a world-unit line set is drawn twice (viser adds an antialiasing
        # pass). Each segment is an instance: about 0.2 ms a frame in a software-rendered browser.
        pending = self._pending(view)
        self._segments("/pending", pending[:0] if dense else pending, MARK_COLORS["pending"], 3.0)
        destinations = pending[:, 1] if dense else pending[:0, 1]  # many robots: a red dot where each goes
        self._points("/pending_cells", destinations, MARK_COLORS["pending"], 0.3, "circle")
        axis = self._line(Line("y", view.axis, "")) if editing_robots and view.axis is not None else None
        self._segments("/axis", axis if axis is not None else np.zeros((0, 2, 3)), MARK_COLORS["axis"], 4.0)
        self._marks(view, pts)
        self._anchor(view)
        x0, _, _, y1 = self.bounds
        # Inside the room the bounds keep for it (3 cells above the run): a framed camera shows it.
        self._labels("/title", [(title, (x0 - 0.5, y1 - 1.0, 0.1))] if title else [])
        if self.layer == "all":
            self._selection(view)

    def _anchor(self, view: SessionView) -> None:
        """Edit: the first click of a two-click tool, marked until the second (a diamond and a word), so
        the drawing is seen to wait for it."""
        at = self._local([view.anchor]) if view.anchor is not None else np.zeros((0, 2), np.float32)
        self._points("/anchor", _xyz(at, _LAYER["anchor"]), MARK_COLORS["anchor"], 1.5, MARK_SHAPES["anchor"])
        said = [
            ("first click: now the second", (float(x) + 0.5, float(y) + 0.35, 0.1)) for x, y in at.tolist()
        ]
        self._labels("/anchor_label", said)

    def _trails(self, view: SessionView) -> None:
        """Each robot's recent path as segments in its light's colour, under the robots, one line set
        per light (as robots are one point cloud per light)."""
        palette = light_colors(view)
        by_light: dict[str, list[np.ndarray]] = {}
        for robot, path in zip(view.robots, view.trails, strict=False):
            if len(path) > 1:
                at = _xyz(self._local(path), 0.04)
                by_light.setdefault(robot.light, []).append(np.stack([at[:-1], at[1:]], axis=1))
        for light in set(self._trail_lights) | set(by_light):
            self._trail_lights.add(light)
            parts = by_light.get(light, [])
            segs = np.concatenate(parts) if parts else np.zeros((0, 2, 3), dtype=np.float32)
            self._segments(f"/trails/{light}", segs, palette.get(light, (0, 0, 0)), 4.0)

    def _selection(self, view: SessionView) -> None:
        """One browser's selection: its ring, rays to what it saw, ghosts, the regions Why tested."""
        sel = view.selected
        at = self._local([view.robots[sel].position] if sel is not None and sel < len(view.robots) else [])
        self._points(
            "/ring/selected",
            _xyz(at, _LAYER["selected"]),
            MARK_COLORS["selected"],
            _SIZE["selected"],
            "circle",
        )
        self._ghosts(view)
        self._hidden(view)
        self._segments("/rays", self._rays(view), MARK_COLORS["ray"], 2.0)
        self._why_regions(view)

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

    def _robots(self, view: SessionView, pts: np.ndarray) -> None:
        """Each robot a flat disc in its light's colour on a dark outline (so a pale light shows on the
        white grid), one point cloud per light: a light change moves a point between clouds instead of
        recolouring one (viser rebuilds a point cloud's material, and the browser its shader, when its
        colours change); a crowd playing, framed whole, without the outlines (``RIM_CROWD``). The
        y-axis is a small dark diamond on the robot's +y side."""
        robots = view.robots[: len(pts)]
        lights = np.array([r.light for r in robots], dtype=object)
        palette = light_colors(view)
        noses, rims = scene_detail(self.view_cells if self.view_cells is not None else self._visible_height())
        rimmed = pts if rims or not view.playing or len(pts) < RIM_CROWD else pts[:0]
        self._points(
            "/robots/outline",
            _xyz(rimmed, _LAYER["outline"]),
            MARK_COLORS["outline"],
            _SIZE["outline"],
            "circle",
        )
        for light in set(self._sprite_lights) | set(lights.tolist()):
            self._sprite_lights.add(light)
            color = palette.get(light, (0, 0, 0))
            self._points(f"/robots/{light}", _xyz(pts[lights == light], Z), color, _SIZE["robot"], "circle")
        shown = pts if noses else pts[:0]
        sign = np.array([1.0 if r.y_up else -1.0 for r in robots[: len(shown)]], dtype=np.float32)
        nose = _xyz(shown, _LAYER["nose"])
        nose[:, 1] += 0.2 * sign
        self._points("/robots/y_axes", nose, (40, 40, 40), NOSE_CELLS, "diamond")

    def _rings(self, view: SessionView, pts: np.ndarray) -> None:
        """Rings under the robots, widest at the bottom: will never act (a grey square, a deadlock),
        acted last (brown), and the phase (yellow: looked, orange: computed; none when idle). The
        selected robot's (black) is its browser's own (:meth:`_selection`)."""
        phases = np.array([r.phase if view.phase_rings else "idle" for r in view.robots])
        for phase in ("looked", "computed"):
            at = pts[phases == phase] if len(phases) else pts[:0]
            self._points(
                f"/phase/{phase}", _xyz(at, _LAYER["phase"]), PHASE_COLORS[phase], _SIZE["phase"], "circle"
            )
        robot = view.last_actor
        at = pts[robot : robot + 1] if robot is not None and robot < len(pts) else pts[:0]
        self._points("/ring/last", _xyz(at, _LAYER["last"]), MARK_COLORS["last"], _SIZE["last"], "circle")
        never = pts[[r for r in view.never_act if r < len(pts)]] if view.never_act else pts[:0]
        self._points(
            "/ring/never",
            _xyz(never, _LAYER["never"]),
            MARK_COLORS["never"],
            _SIZE["never"],
            MARK_SHAPES["never"],
        )

    def _ghosts(self, view: SessionView) -> None:
        """Where the selected robot saw robots that have moved or changed light since: a disc in the light
        it saw, on a grey outline, numbered with the robot's number and a prime ("3′": robot 3, then). A
        robot that only changed light is still where it was seen: its ghost is a small badge at the
        robot's upper left, so that the robot does not cover it."""
        places = self._local([g.at for g in view.ghosts])
        badge = np.array([g.light_only for g in view.ghosts], dtype=bool)
        places[badge] += np.array(GHOST_BADGE_OFFSET, dtype=np.float32)
        lights = np.array([g.light for g in view.ghosts], dtype=object)
        palette = light_colors(view)
        for kind, which, size in (("full", ~badge, 1.0), ("badge", badge, 0.6)):
            self._points(
                f"/ghosts/{kind}/outline",
                _xyz(places[which], _LAYER["ghost_outline"] + (0.06 if kind == "badge" else 0)),
                MARK_COLORS["ghost"],
                0.62 * size,
                "circle",
            )
            for light in set(self._ghost_lights) | set(lights.tolist()):
                self._ghost_lights.add(light)
                pick = which & (lights == light) if len(lights) else which
                self._points(
                    f"/ghosts/{kind}/{light}",
                    _xyz(places[pick], _LAYER["ghost"] + (0.06 if kind == "badge" else 0)),
                    palette.get(light, (0, 0, 0)),
                    0.44 * size,
                    "circle",
                )
        numbers = [
            (f"{g.robot}′", (float(x) + 0.2, float(y) + 0.22, 0.7))
            for g, (x, y) in zip(view.ghosts, places.tolist(), strict=True)
        ]
        self._labels("/ghosts/numbers", numbers)

    def _hidden(self, view: SessionView) -> None:
        """The robots the selected robot cannot see, greyed (a pale disc over their light), and on each
        robot that hides one a small dark square with a thin grey line on to what it hides."""
        where = {i: r.position for i, r in enumerate(view.robots)}
        hidden = self._local([where[j] for j in view.hidden if j in where])
        self._points("/hidden", _xyz(hidden, _LAYER["fog"]), MARK_COLORS["hidden"], 0.42, "circle")
        pairs = [(where[h], where[j]) for h, j in view.hiders if h in where and j in where]
        hiders = self._local(sorted({a for a, _ in pairs}))
        self._points("/hiders", _xyz(hiders, _LAYER["fog"]), MARK_COLORS["hider"], 0.2, "square")
        segs = np.zeros((len(pairs), 2, 3), dtype=np.float32)
        if pairs:
            segs[:, 0, :] = _xyz(self._local([a for a, _ in pairs]), 0.03)
            segs[:, 1, :] = _xyz(self._local([b for _, b in pairs]), 0.03)
        self._segments("/hides", segs, MARK_COLORS["hidden_line"], 1.5)

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

    def _grid(self) -> None:
        x0, y0, x1, y1 = self.bounds
        key = (int(np.floor(x0)) - 6, int(np.floor(y0)) - 6, int(np.ceil(x1)) + 6, int(np.ceil(y1)) + 6)
        if (
            self._grid_key is not None
            and all(a <= b for a, b in zip(self._grid_key[:2], key[:2], strict=True))
            and all(a >= b for a, b in zip(self._grid_key[2:], key[2:], strict=True))
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

    def _rays(self, view: SessionView) -> np.ndarray:
        if not view.rays:
            return np.zeros((0, 2, 3))
        a = self._local(np.array(view.rays, dtype=np.int64).reshape(-1, 2)).reshape(-1, 2, 2)
        return np.concatenate([a, np.full((len(a), 2, 1), Z - 0.01, dtype=np.float32)], axis=2)

    def _pending(self, view: SessionView) -> np.ndarray:
        pairs = [(r.position, r.pending) for r in view.robots if r.pending is not None]
        ends = self._local(np.array(pairs, dtype=np.int64).reshape(-1, 2)).reshape(-1, 2, 2)
        return np.concatenate([ends, np.full((len(ends), 2, 1), Z + 0.04, dtype=np.float32)], axis=2)

    # ------------------------------------------------------------------ the algorithm's marks
    def _targets(self, view: SessionView) -> None:
        """The first set of cells the algorithm gives (where the pattern forms), or the pattern drawn."""
        cells = next((m for m in view.overlays.marks if isinstance(m, Cells)), None)
        style = cells.style if cells else "placed"  # the legend shows the same swatch
        points = self._local(cells.points if cells else ())
        self._points("/targets", _xyz(points, 0.005), TARGET_COLORS[style], 0.8)

    def _marks(self, view: SessionView, robots: np.ndarray) -> None:
        """Lines and frames of the overlays, each labelled on the canvas (``robots``: their scene points; a
        label goes where none is). A handful per run: a node each, created once per slot and updated in
        place."""
        lines = [m for m in view.overlays.marks if isinstance(m, Line)]
        frames = [m for m in view.overlays.marks if isinstance(m, Frame)]
        labels: list[tuple[str, tuple[float, float, float]]] = []
        for i in range(max(len(lines), self._slots.get("line", 0))):
            mark = lines[i] if i < len(lines) else None
            segs = self._line(mark) if mark else np.zeros((0, 2, 3), np.float32)
            color = (mark.color if mark else None) or MARK_COLORS["line"]
            self._segments(f"/marks/line{i}", segs, color, 3.0)
            if mark:
                labels.append((mark.label, tuple(segs[0, 1])))
        self._slots["line"] = max(len(lines), self._slots.get("line", 0))
        height = text_cells(self._visible_height())
        taken = []  # the cells' label first: a frame's label has more places to go
        cells = next((m for m in view.overlays.marks if isinstance(m, Cells)), None)
        if cells is not None and cells.points and view.mode != "edit-pattern":
            local = self._local(cells.points)
            spot = cells_label_at(local, robots, cells.label, height)
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

    def _line(self, mark: Line) -> np.ndarray:
        x0, y0, x1, y1 = self.bounds
        if mark.axis == "y":
            y = mark.at - self.origin[1]
            return np.array([[(x0 - 2, y, 0.05), (x1 + 2, y, 0.05)]], dtype=np.float32)
        x = mark.at - self.origin[0]
        return np.array([[(x, y0 - 2, 0.05), (x, y1 + 2, 0.05)]], dtype=np.float32)

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

    def _labels(self, prefix: str, labels: list[tuple[str, tuple[float, float, float]]]) -> None:
        """Text on the canvas, one node per slot, updated in place (text and position) and hidden when
        unused."""
        key = tuple(labels)
        if self._last.get(prefix) == (key, None, None):
            return
        self._last[prefix] = (key, None, None)
        used = self._slots.get(prefix, 0)
        for i in range(max(used, len(labels))):
            name = f"{prefix}/{i}"
            handle = self._handles.get(name)
            if i < len(labels):
                text, position = labels[i]
                text = canvas_symbol(text)
                if handle is None:
                    self._handles[name] = self.scene.add_label(
                        self.prefix + name,
                        text,
                        position=position,
                        font_screen_scale=LABEL_SCALE,
                        anchor="bottom-left",
                    )
                else:
                    handle.text = text  # type: ignore[attr-defined]
                    handle.position = position  # type: ignore[attr-defined]
                    handle.visible = True  # type: ignore[attr-defined]
            elif handle is not None:
                handle.visible = False  # type: ignore[attr-defined]
        self._slots[prefix] = max(used, len(labels))

    # ------------------------------------------------------------------ why: the regions a rule tested
    def _why_regions(self, view: SessionView) -> None:
        """The selected robot's regions, translucent so robots stay visible: half planes and bands as
        flat quads, lines as segments, each in its own colour and labelled with the number the Why panel
        gives it. Re-made only when they change (a selection or a decision), so a playing run pays
        nothing for them."""
        regions = view.why.regions if view.why is not None else ()
        if self._last.get("/why") == (regions, None, None):
            return
        self._last["/why"] = (regions, None, None)
        for name in [n for n in self._handles if n.startswith(("/why/area", "/why/line"))]:
            self._handles.pop(name).remove()  # type: ignore[attr-defined]
        labels = []
        for i, mark in enumerate(regions):
            at = self._why_line(i, mark) if isinstance(mark, Line) else None
            if isinstance(mark, HalfPlane | Band):
                at = self._why_area(i, mark)
            if at is not None:
                labels.append((f"{i + 1} · {mark.label}", at))
        self._labels("/why/labels", labels)

    def _why_line(self, i: int, mark: Line) -> tuple[float, float, float]:
        """A tested line as a segment; its label's place, inside the framed run (the line runs on)."""
        _, _, x1, y1 = self.bounds
        seg = self._line(mark)
        self._handles[f"/why/line{i}"] = self.scene.add_line_segments(
            f"{self.prefix}/why/line{i}",
            seg[:1].astype(np.float32),
            region_color(i),
            thickness=3.0,
            thickness_units="screen",
        )
        if mark.axis == "y":
            return (x1 - 3.0, float(seg[0, 1, 1]) + 0.15, 0.1)
        return (float(seg[0, 1, 0]) + 0.2, y1, 0.1)

    def _why_area(self, i: int, mark: HalfPlane | Band) -> tuple[float, float, float] | None:
        """A tested half plane or band as a translucent quad clipped a little beyond the run; its
        label's place inside the run's bounds, which the camera frames (None: nothing of it shows)."""
        x0, y0, x1, y1 = self.bounds
        box = (x0 - 3, y0 - 3, x1 + 3, y1 + 3)
        lo, hi = self._extent(mark)
        rect = (lo, box[1], hi, box[3]) if mark.axis == "x" else (box[0], lo, box[2], hi)
        rect = (max(rect[0], box[0]), max(rect[1], box[1]), min(rect[2], box[2]), min(rect[3], box[3]))
        if rect[0] >= rect[2] or rect[1] >= rect[3]:
            return None
        corners = [(rect[0], rect[1]), (rect[2], rect[1]), (rect[2], rect[3]), (rect[0], rect[3])]
        self._handles[f"/why/area{i}"] = self.scene.add_mesh_simple(
            f"{self.prefix}/why/area{i}",
            np.array([(x, y, 0.02) for x, y in corners], dtype=np.float32),
            np.array([(0, 1, 2), (0, 2, 3)], dtype=np.uint32),
            color=region_color(i),
            opacity=REGION_OPACITY,
            side="double",
            cast_shadow=False,
            receive_shadow=False,
        )
        inner = (max(rect[0], x0), max(rect[1], y0), min(rect[2], x1), min(rect[3], y1))
        inside = inner[0] < inner[2] and inner[1] < inner[3]
        return self._region_label_at(mark, inner if inside else rect)

    def _extent(self, mark: HalfPlane | Band) -> tuple[float, float]:
        """The region's span on its axis, in scene units (a half plane reaches far; the caller clips)."""
        shift = self.origin[0] if mark.axis == "x" else self.origin[1]
        far = 1e6
        if isinstance(mark, Band):
            return mark.lo - shift - 0.5, mark.hi - shift + 0.5
        edge = mark.at - shift + (0.5 if mark.closed else -0.5) * mark.side * -1
        # closed: the boundary row/column is inside (the area starts half a cell beyond it); open: not
        return (edge, far) if mark.side > 0 else (-far, edge)

    @staticmethod
    def _region_label_at(mark: HalfPlane | Band, rect: tuple[float, ...]) -> tuple[float, float, float]:
        """Near the region's boundary on the robot's side, where a reader looks."""
        x0, y0, x1, y1 = rect
        if mark.axis == "x":
            x = x1 - 1.6 if isinstance(mark, HalfPlane) and mark.side < 0 else x0 + 0.2
            return (x, y1 - 0.3, 0.1)
        y = y1 - 0.3 if isinstance(mark, HalfPlane) and mark.side < 0 else y0 + 0.3
        return (x0 + 0.2, y, 0.1)

    # ------------------------------------------------------------------ camera
    def camera_pose(
        self,
        aspect: float = NARROW_ASPECT,
        caption_room: float = 0.0,
        bounds: Bounds | None = None,
    ) -> tuple[tuple[float, float, float], tuple[float, float, float], float]:
        """(position, look_at, fov) of a top-down view of the whole run (start, pattern, in between), for
        a canvas ``aspect`` = width / height (the field of view is vertical, so a narrow canvas needs the
        camera higher to fit the run's width); ``caption_room``: the share of the canvas's height to
        leave free at the bottom (presentation mode's caption floats there, clear of the notifications,
        which the page shows at the top left). ``bounds``: a box to show instead of
        the run's own (one with room to grow, :func:`grown_box`)."""
        x0, y0, x1, y1 = self.bounds if bounds is None else bounds
        cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
        fov = float(np.deg2rad(50))
        extent = max((y1 - y0 + 4) / (1 - caption_room), (x1 - x0 + 4) / max(aspect, 0.2), 10)
        cy -= caption_room * extent / 2  # the run in the middle of the canvas's upper part
        h = extent / (2 * np.tan(fov / 2))
        # A little south of straight above: the orbit controls need a direction that is not "up".
        return (cx, cy - 0.05 * h, h), (cx, cy, 0.0), fov

    def _visible_height(self) -> float:
        """How many cells tall the framed view is (the initial camera's pose: what browsers are framed
        to, near enough for laying out labels)."""
        position, look_at, fov = self.framed_pose
        return 2.0 * abs(position[2] - look_at[2]) * float(np.tan(fov / 2))

    def frame_initial_camera(self, initial, bounds: Bounds | None = None) -> None:
        """The pose new browsers start from (and "Reset View" returns to): the run, or ``bounds``."""
        position, look_at, fov = self.framed_pose = self.camera_pose(bounds=bounds)
        initial.fov = fov
        initial.up = (0.0, 0.0, 1.0)
        initial.position = position
        initial.look_at = look_at

    def frame_camera(
        self, camera, caption_room: float = 0.0, bounds: Bounds | None = None
    ) -> tuple[tuple[float, float, float] | None, float]:
        """Move a connected browser's camera to the whole run, or to ``bounds`` (position first: it drags
        look_at along), fitted to that browser's canvas (``caption_room``: :meth:`camera_pose`). Returns the
        position sent (None if none could be) and the aspect it was fitted to."""
        aspect = camera_aspect(camera)
        position, look_at, fov = self.camera_pose(aspect, caption_room, bounds)
        try:
            camera.fov = _unskipped(camera.fov, fov)
            camera.position = _unskipped(camera.position, position)
            camera.look_at = _unskipped(camera.look_at, look_at)
        except AssertionError:
            return None, aspect  # the browser has not reported its camera yet; its initial pose is right
        return position, aspect


def _unskipped(held, wanted):
    """``wanted``, or a hair off it when it equals what viser holds for the browser's camera: viser drops
    a value equal to the one it holds, and what it holds may be the browser's late report while the page
    is still on its way to an earlier pose (sent B, reported A, sent A: dropped, and the page came to
    rest at B). The hair is 1e-4 of the last coordinate (the camera's height; a scalar's size), past
    viser's 1e-5 and far inside what counts as the same pose (``app._same_pose``, 1e-3 of the height)."""
    held_, wanted_ = np.asarray(held, dtype=float), np.array(wanted, dtype=float)
    if not np.allclose(held_, wanted_):
        return wanted
    last = wanted_.reshape(-1)
    last[-1] += 1e-4 * max(abs(last[-1]), 1.0)
    return float(wanted_) if wanted_.ndim == 0 else tuple(float(v) for v in wanted_)


GROWTH_ROOM = 0.2
"""Of the run's extent: the room a camera re-framed for a growing run leaves beyond each side it grew."""


def grown_box(box: Bounds, framed: Bounds) -> Bounds:
    """What a camera shows when the run (``box``) has grown out of the ``framed`` box: both, with room
    beyond each side that grew. A run that grows a cell at a time (the line reaching out from the leader,
    a robot walking away) then moves the camera every few cells, not at every frame: a steadier picture,
    and no camera messages in the frames between."""
    room = GROWTH_ROOM * max(box[2] - box[0], box[3] - box[1], 5.0)
    return (
        box[0] - room if box[0] < framed[0] else framed[0],
        box[1] - room if box[1] < framed[1] else framed[1],
        box[2] + room if box[2] > framed[2] else framed[2],
        box[3] + room if box[3] > framed[3] else framed[3],
    )


LABEL_TEXT_PX = 15.0  # a label's height on screen, padding included (viser's labels keep a screen size)
TYPICAL_CANVAS_PX = 800.0  # the canvas height labels are laid out for (1400×900 and 1024×768 windows)
TEXT_CELLS_MIN = 0.35  # a label's height in cells when zoomed in (the layout's fixed offsets assume it)

Spot = tuple[float, float, float]  # (x, y, x where the text ends), in scene units


def scene_detail(visible_height: float) -> tuple[bool, bool]:
    """What is drawn of the robots when the canvas shows ``visible_height`` cells: (the y-axis
    diamonds, wide enough on screen to be seen; the outlines even while playing, a cell at least
    ``RIM_PLAYING_PX`` wide)."""
    cell_px = TYPICAL_CANVAS_PX / max(visible_height, 1e-9)
    return NOSE_CELLS * cell_px >= NOSE_MIN_PX, cell_px >= RIM_PLAYING_PX


def camera_cells(camera) -> float | None:
    """How many cells tall a browser's camera shows at the grid (None before it has reported)."""
    try:
        position = np.asarray(camera.position, dtype=float)
        look_at = np.asarray(camera.look_at, dtype=float)
        fov = float(camera.fov)
    except (AssertionError, TypeError, ValueError):
        return None
    return 2.0 * float(np.linalg.norm(position - look_at)) * float(np.tan(fov / 2))


def text_cells(visible_height: float) -> float:
    """A label's height in grid cells when the canvas shows ``visible_height`` cells: a label keeps its
    size on screen, so zoomed out over a large run it is several cells tall."""
    return max(TEXT_CELLS_MIN, LABEL_TEXT_PX * visible_height / TYPICAL_CANVAS_PX)


def label_box(text: str, spot: Spot, height: float) -> Bounds:
    """The rectangle (x0, y0, x1, y1) a label's text covers, drawn from ``spot`` (its lower left)."""
    x, y, x_end = spot
    return (x, y - 0.25, max(x_end, x + 0.55 * height * len(text)), y - 0.25 + max(0.5, height))


def _overlaps(a: Bounds, b: Bounds) -> bool:
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


def free_label_spot(
    spots: list[Spot],
    robots: np.ndarray,
    text: str = "",
    height: float = TEXT_CELLS_MIN,
    taken: list[Bounds] | None = None,
) -> tuple[float, float, float]:
    """The first of ``spots`` where the text covers no robot, no robot's number (upper right of its
    disc) and no label already placed (``taken``: their :func:`label_box`); else the first that covers
    no label (a label over a robot still reads, two labels over each other do not); else the first."""
    taken = taken or []
    clear_of_labels = []
    for spot in spots:
        box = label_box(text, spot, height)
        if any(_overlaps(box, t) for t in taken):
            continue
        clear_of_labels.append(spot)
        covered = (
            (robots[:, 1] - 0.4 < box[3])
            & (robots[:, 1] + 0.7 > box[1])
            & (robots[:, 0] - 0.5 < box[2])
            & (robots[:, 0] + 0.7 > box[0])
        )
        if not covered.any():
            return (spot[0], spot[1], 0.1)
    x, y, _ = (clear_of_labels or spots)[0]
    return (x, y, 0.1)


def cells_label_at(
    cells: np.ndarray, robots: np.ndarray, text: str = "", height: float = TEXT_CELLS_MIN
) -> tuple[float, float, float]:
    """Where a set of cells' label goes: just above their top row; when a robot stands where the text
    would be (a pattern drawn among the robots, as the Unsolvable box demo's is), just below their bottom
    row, else to the right of their top row. So the label does not cover a robot."""
    left, right = float(cells[:, 0].min()) - 0.4, float(cells[:, 0].max())
    top, bottom = float(cells[:, 1].max()), float(cells[:, 1].min())
    below = bottom - 0.55 - height  # its text ends just under the bottom row, however tall it is
    return free_label_spot(
        [(left, top + 0.6, right + 0.5), (left, below, right + 0.5), (right + 0.7, top, right + 3.7)],
        robots,
        text,
        height,
    )


def frame_label_at(
    origin: tuple[float, float],
    y_sign: int,
    robots: np.ndarray,
    text: str = "",
    height: float = TEXT_CELLS_MIN,
    taken: list[Bounds] | None = None,
) -> tuple[float, float, float]:
    """Where a frame's label goes: under its origin (on the side away from its +y arm), else beyond the
    end of its x arm, else past the tip of its y arm; not over a robot or its number where one of these
    is free (the leader's neighbours crowd its row), never over another label (``taken``) where one is
    free of labels, and under the origin when none is."""
    ox, oy = origin
    away = oy + 0.6 if y_sign < 0 else oy - 0.25 - height
    tip = oy + 2.6 if y_sign > 0 else oy - 2.25 - height
    under, beyond_x = (ox, away, ox + 3.0), (ox + 2.4, oy, ox + 5.4)
    return free_label_spot([under, beyond_x, (ox - 0.4, tip, ox + 2.6)], robots, text, height, taken)


def ray_through(camera, screen: tuple[float, float]) -> tuple[np.ndarray, np.ndarray]:
    """The ray from a browser's camera through a point of its canvas (``screen``: 0..1 each way, from
    the top-left, as viser reports a dragged box), in scene coordinates."""
    p = np.asarray(camera.position, dtype=float)
    forward = np.asarray(camera.look_at, dtype=float) - p
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    t = np.tan(float(camera.fov) / 2)
    x, y = 2 * screen[0] - 1, 1 - 2 * screen[1]
    return p, forward + x * t * camera_aspect(camera) * right + y * t * up


def camera_aspect(camera) -> float:
    """The width / height of a browser's canvas, as its camera reports it (before it has: the narrow
    canvas new browsers are framed for)."""
    try:
        aspect = float(camera.aspect)
    except (AssertionError, AttributeError, TypeError, ValueError):
        return NARROW_ASPECT
    return aspect if aspect == aspect and aspect > 0 else NARROW_ASPECT


def cell_of_ray(origin, direction) -> tuple[int, int] | None:
    """The grid cell a click ray hits on the plane z = 0 (robots are small, so the cell is enough)."""
    ox, oy, oz = origin
    dx, dy, dz = direction
    if abs(dz) < 1e-9:
        return None
    t = -oz / dz
    if t < 0:
        return None
    x, y = ox + t * dx, oy + t * dy
    if not (math.isfinite(x) and math.isfinite(y)):
        return None  # a browser may send any ray
    return (round(x), round(y))
