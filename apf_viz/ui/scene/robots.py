"""The robots: discs in their light's colour, y-axis diamonds, rings, trails and an edit tool's anchor."""

from __future__ import annotations

import itertools

import numpy as np

from apf_viz.core.portrayal import Line
from apf_viz.ui.scene.camera import scene_detail
from apf_viz.ui.scene.canvas import Canvas
from apf_viz.ui.scene.style import LAYER, NOSE_CELLS, RIM_CROWD, SIZE, Z, light_colors, xyz
from apf_viz.workbench.palette import MARK_COLORS, MARK_SHAPES, PHASE_COLORS
from apf_viz.workbench.view_model import SessionView


class RobotsLayer(Canvas):
    """Draws the run's robots."""

    def _robots(self, view: SessionView, pts: np.ndarray) -> None:
        """Each robot a flat disc in its light's colour on a dark outline (so a pale light shows on the
        white grid), one point cloud per light: a light change moves a point between clouds instead of
        recolouring one (viser rebuilds a point cloud's material, and the browser its shader, when its
        colours change); a crowd playing, framed whole, without the outlines (``RIM_CROWD``). The
        y-axis is a small dark diamond on the robot's +y side."""
        robots = view.robots[: len(pts)]
        lights = np.array([r.light for r in robots], dtype=object)
        palette = light_colors(view)
        noses, rims = scene_detail(self.view_cells if self.view_cells is not None else self.visible_height())
        rimmed = pts if rims or not view.playing or len(pts) < RIM_CROWD else pts[:0]
        squares = np.array([view.legend[r.light].shape == "square" if r.light in view.legend else False
                            for r in robots], dtype=bool)  # fmt: skip
        for suffix, of_shape in (("", ~squares), ("-square", squares)):  # a rim of the robot's shape
            self._points(
                "/robots/outline" + suffix,
                xyz(rimmed[of_shape[: len(rimmed)]], LAYER["outline"]),
                MARK_COLORS["outline"],
                SIZE["outline"],
                "square" if suffix else "circle",
            )
        # A cloud a light and shape (a cloud's shape is fixed when it is made; another algorithm may draw
        # a light of the same name otherwise).
        drawn = list(zip(lights.tolist(), squares.tolist(), strict=True))
        for light, square in set(self._sprite_lights) | set(drawn):
            self._sprite_lights.add((light, square))
            at = xyz(pts[[kind == (light, square) for kind in drawn]], Z)
            name = f"/robots/{light}" + ("-square" if square else "")
            color = palette.get(light, (0, 0, 0))
            self._points(name, at, color, SIZE["robot"], "square" if square else "circle")
        shown = pts if noses else pts[:0]
        sign = np.array([1.0 if r.y_up else -1.0 for r in robots[: len(shown)]], dtype=np.float32)
        nose = xyz(shown, LAYER["nose"])
        nose[:, 1] += 0.2 * sign
        self._points("/robots/y_axes", nose, (40, 40, 40), NOSE_CELLS, "diamond")

    def _rings(self, view: SessionView, pts: np.ndarray) -> None:
        """Rings under the robots, widest at the bottom: will never act (a grey square, a deadlock),
        acted last (brown), and the phase (yellow: looked, orange: computed; none when idle). The
        selected robot's (black) is its browser's own (a
        :class:`~apf_viz.ui.scene.selection.SelectionRenderer`)."""
        phases = np.array([r.phase if view.phase_rings else "idle" for r in view.robots])
        for phase in ("looked", "computed"):
            at = pts[phases == phase] if len(phases) else pts[:0]
            self._points(
                f"/phase/{phase}", xyz(at, LAYER["phase"]), PHASE_COLORS[phase], SIZE["phase"], "circle"
            )
        robot = view.last_actor
        at = pts[robot : robot + 1] if robot is not None and robot < len(pts) else pts[:0]
        self._points("/ring/last", xyz(at, LAYER["last"]), MARK_COLORS["last"], SIZE["last"], "circle")
        never = pts[[r for r in view.never_act if r < len(pts)]] if view.never_act else pts[:0]
        self._points(
            "/ring/never",
            xyz(never, LAYER["never"]),
            MARK_COLORS["never"],
            SIZE["never"],
            MARK_SHAPES["never"],
        )

    def _trails(self, view: SessionView) -> None:
        """Each robot's recent path as segments in its light's colour, under the robots, one line set
        per light (as robots are one point cloud per light)."""
        palette = light_colors(view)
        by_light: dict[str, list[np.ndarray]] = {}
        for robot, path in zip(view.robots, view.trails, strict=False):
            if len(path) > 1:
                at = xyz(self._local(path), 0.04)
                by_light.setdefault(robot.light, []).append(np.stack([at[:-1], at[1:]], axis=1))
        for light in set(self._trail_lights) | set(by_light):
            self._trail_lights.add(light)
            parts = by_light.get(light, [])
            segs = np.concatenate(parts) if parts else np.zeros((0, 2, 3), dtype=np.float32)
            self._segments(f"/trails/{light}", segs, palette.get(light, (0, 0, 0)), 4.0)

    def _anchor(self, view: SessionView) -> None:
        """Edit: the first click of a two-click tool, marked until the second (a diamond and a word), so
        the drawing is seen to wait for it."""
        at = self._local([view.anchor]) if view.anchor is not None else np.zeros((0, 2), np.float32)
        self._points("/anchor", xyz(at, LAYER["anchor"]), MARK_COLORS["anchor"], 1.5, MARK_SHAPES["anchor"])
        said = [
            ("first click: now the second", (float(x) + 0.5, float(y) + 0.35, 0.1)) for x, y in at.tolist()
        ]
        self._labels("/anchor_label", said)

    def _studio(self, view: SessionView) -> None:
        """Edit: the selection's box (dashes round the cells it took) and the live mirror's axes."""
        segments = np.zeros((0, 2, 3), np.float32)
        if view.selection_box is not None:
            (xa, ya), (xb, yb) = self._local(list(view.selection_box)).tolist()
            x0, x1 = min(xa, xb) - 0.5, max(xa, xb) + 0.5
            y0, y1 = min(ya, yb) - 0.5, max(ya, yb) + 0.5
            corners = [(x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)]
            segments = np.array(
                [[(*a, 0.07), (*b, 0.07)] for a, b in itertools.pairwise(corners)], np.float32
            )
        self._segments("/studio/selection", segments, MARK_COLORS["selected"], 2.0)
        mirror_x, mirror_y = view.mirror_axes
        axes = [Line("x", mirror_x, "")] if mirror_x is not None else []
        axes += [Line("y", mirror_y, "")] if mirror_y is not None else []
        lines = np.concatenate([self._line(a) for a in axes]) if axes else np.zeros((0, 2, 3), np.float32)
        self._segments("/studio/mirror", lines, MARK_COLORS["axis"], 2.0)
