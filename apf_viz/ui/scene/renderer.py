"""A frame of the scene: each layer drawn in its order."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from apf_viz.core.portrayal import Line
from apf_viz.core.schedulers import BY_HAND
from apf_viz.ui.scene.framing import Framing
from apf_viz.ui.scene.grid import GridLayer
from apf_viz.ui.scene.labels import number_labels, spec_box, spread
from apf_viz.ui.scene.marks import MarksLayer
from apf_viz.ui.scene.robots import RobotsLayer
from apf_viz.ui.scene.selection import SelectionRenderer
from apf_viz.ui.scene.style import DENSE, LABEL_ROOM, LAYER, Bounds, xyz
from apf_viz.workbench.palette import MARK_COLORS, MARK_SHAPES
from apf_viz.workbench.view_model import SessionView

NEXT_PHASE = {"idle": "look", "looked": "compute", "computed": "move"}  # Manual: what a click runs
SPREAD_UP_TO = 60  # labels: beyond, each keeps its robot's upper right (see labels.spread)


class SceneRenderer(RobotsLayer, GridLayer, MarksLayer, Framing):
    """Draws session views into one scene: the server's (every browser) or one browser's.

    It draws what every browser shares (robots, rings, targets, the algorithm's marks). With
    ``selection`` (a scene one browser alone sees: its own run, a test's), its part
    :attr:`selection` draws the view's selection too (ring, rays, ghosts, Why's regions); the shared
    run's selection is each browser's own :class:`SelectionRenderer`, in its own scene."""

    def __init__(self, owner, prefix: str = "", root: str = "", selection: bool = True) -> None:
        super().__init__(owner, prefix, root)
        if not prefix:
            # The scene's own settings, once: a second renderer in the same scene (Compare) setting the
            # up direction again makes every page reset its camera to the initial pose.
            self.scene.set_up_direction("+z")
            # Nothing here casts a shadow, but lights that may cast one make the browser clear three
            # 1024² shadow maps every frame: a tenth of a software-rendered frame (docs/PERFORMANCE.md).
            self.scene.configure_default_lights(enabled=True, cast_shadow=False)
        self.selection = SelectionRenderer(owner, self, root, prefix) if selection else None

    def nodes(self) -> dict[str, object]:
        nodes = super().nodes()
        if self.selection is not None:
            nodes.update(self.selection.nodes())
        return nodes

    def clear(self) -> None:
        super().clear()
        if self.selection is not None:
            self.selection.clear()

    # ------------------------------------------------------------------ drawing
    def render(self, view: SessionView, title: str | None = None, beside: Sequence[Bounds] = ()) -> None:
        """Draw one frame; the caller wraps it in ``server.atomic()``. ``title``: a label above the run
        (Compare names each side); ``beside``: the labels another run in the same scene has placed (the
        first of Compare's), which this one's words keep clear of. Its own labels' boxes are kept in
        :attr:`label_boxes`."""
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
        said_boxes = self._robot_labels(view, pts, title, beside)
        split = pts[view.diverged : view.diverged + 1] if view.diverged is not None else pts[:0]
        self._points("/diverged", xyz(split, LAYER["diverged"]), MARK_COLORS["diverged"], 1.5, "diamond")
        crash = self._local(view.collision[1]) if view.collision else pts[:0]
        self._points("/collision", xyz(crash, 0.006), MARK_COLORS["collision"], 1.6, MARK_SHAPES["collision"])
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
        placed = self._marks(view, pts, said_boxes)
        self._anchor(view)
        self._studio(view)
        x0, _, x1, y1 = self.bounds
        # Inside the room the bounds keep for it (3 cells above the run): a framed camera shows it. The
        # run on the right of Compare has its title end where the room kept right of it ends, running
        # left over the gap between the runs: from its left end it ran off the canvas.
        spec = (
            (title, (x1 + LABEL_ROOM - 0.5, y1 - 1.0, 0.1), "bottom-right")
            if self.prefix
            else (title, (x0 - 0.5, y1 - 1.0, 0.1))
        )
        self._labels("/title", [spec] if title else [])
        height = self._text_height()
        titled = [spec_box(spec, height)] if title else []
        self.label_boxes = placed[len(beside) :] + titled
        if self.selection is not None:
            self.selection.render(view)

    def _robot_labels(
        self, view: SessionView, pts: np.ndarray, title: str | None, beside: Sequence[Bounds]
    ) -> list:
        """Each robot's label (its number, and what is said of it); returns ``beside`` and their boxes, for
        the marks' labels to keep clear of."""
        # Manual's next phases join the numbers: a crowd shown without numbers gets no label per robot.
        by_hand = view.scheduler in BY_HAND and view.mode == "run" and view.outcome is None and view.numbers
        next_phase = tuple(NEXT_PHASE.get(r.phase, "") for r in view.robots) if by_hand else ()
        # Compare (a title above each run) frames two runs small: only the numbers there, where a word
        # beside a robot would cover its neighbours; the robot where they part has its diamond, and the
        # caption says which it is and when. A selected robot still shows its ghosts.
        stale = () if title else view.stale_holders
        said = number_labels(pts.tolist(), view.numbers, stale, None if title else view.diverged, next_phase)
        height = self._text_height()
        # Words beside numbers: room made for them, among a few robots (a pass over every pair of labels;
        # in a crowd the labels overlap whatever their places).
        if len(said) <= SPREAD_UP_TO and not all(text.isdigit() for text, _ in said):
            # A framed camera shows 2 cells beyond the run's box (scene.camera.pose_for's extent + 4); the
            # run on the right of Compare has the gap between the runs on its left.
            edge = -float("inf") if self.prefix else self.bounds[0] - 1.5
            said = spread(said, pts.tolist(), height, left_edge=edge, taken=beside)
        self._labels("/numbers", said)
        # The marks' labels ("the leader's frame", "targets") go where the robots' labels are not.
        own = [spec_box(spec, height) for spec in said] if len(said) <= SPREAD_UP_TO else []
        said_boxes = [*beside, *own]
        return said_boxes
