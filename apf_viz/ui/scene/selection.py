"""One browser's selection: its ring, rays to what it saw, ghosts, the robots it cannot see and the
regions Why tested."""

from __future__ import annotations

import numpy as np

from apf_viz.core.portrayal import Band, HalfPlane, Line
from apf_viz.ui.scene.canvas import Canvas
from apf_viz.ui.scene.labels import free_label_spot, label_box, place_near, robot_discs
from apf_viz.ui.scene.style import (
    FULL_CANVAS_MATERIAL,
    GHOST_BADGE_OFFSET,
    LAYER,
    REGION_OPACITY,
    SIZE,
    Z,
    light_colors,
    xyz,
)
from apf_viz.workbench.palette import MARK_COLORS, region_color
from apf_viz.workbench.view_model import SessionView


class SelectionRenderer(Canvas):
    """Draws a browser's selection, in that browser's own scene, over the run ``base`` draws (its origin,
    its bounds, its labels kept clear of, its label height): a part of its own, not a mode of the run's
    renderer."""

    def __init__(self, owner, base: Canvas, root: str = "", prefix: str = "") -> None:
        super().__init__(owner, prefix, root)
        self.base = base

    def render(self, view: SessionView) -> None:
        """Draw the selection of ``view`` (the caller wraps it in the scene's ``atomic()``)."""
        self.origin, self.bounds = self.base.origin, self.base.bounds
        self._selection(view)

    def _text_height(self) -> float:
        return self.base._text_height()  # over the run's labels: laid out at their size

    def _selection(self, view: SessionView) -> None:
        """One browser's selection: its ring, rays to what it saw, ghosts, the regions Why tested. Drawn
        only when what it is drawn from changed (a class's pages would otherwise redo it in every turn
        of every page, for a robot that has not moved)."""
        drawn = _selection_inputs(view, self.origin, self.bounds)
        inputs = (drawn, tuple(self._taken()), self._text_height())
        if self._last.get("/selection") == (inputs, None, None):
            return
        self._last["/selection"] = (inputs, None, None)
        sel = view.selected
        at = self._local([view.robots[sel].position] if sel is not None and sel < len(view.robots) else [])
        self._points(
            "/ring/selected",
            xyz(at, LAYER["selected"]),
            MARK_COLORS["selected"],
            SIZE["selected"],
            "circle",
        )
        taken = self._ghosts(view)
        self._hidden(view)
        self._segments("/rays", self._rays(view), MARK_COLORS["ray"], 2.0)
        self._why_regions(view, taken)

    def _ghosts(self, view: SessionView) -> list:
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
                xyz(places[which], LAYER["ghost_outline"] + (0.06 if kind == "badge" else 0)),
                MARK_COLORS["ghost"],
                0.62 * size,
                "circle",
            )
            for light in set(self._ghost_lights) | set(lights.tolist()):
                self._ghost_lights.add(light)
                pick = which & (lights == light) if len(lights) else which
                self._points(
                    f"/ghosts/{kind}/{light}",
                    xyz(places[pick], LAYER["ghost"] + (0.06 if kind == "badge" else 0)),
                    palette.get(light, (0, 0, 0)),
                    0.44 * size,
                    "circle",
                )
        # Each ghost's number touching its ghost, clear of the run's labels and of each other.
        height, taken, robots = self._text_height(), self._taken(), self._robot_points(view)
        discs = robot_discs(robots.tolist())
        numbers = []
        for g, (x, y) in zip(view.ghosts, places.tolist(), strict=True):
            text = f"{g.robot}′"
            (ax, ay), anchor, box = place_near(text, (x, y), height, taken, discs)
            taken.append(box)
            numbers.append((text, (ax, ay, 0.7), anchor))
        self._labels("/ghosts/numbers", numbers)
        return taken  # the run's labels and the ghosts' numbers

    def _taken(self) -> list:
        """The labels already on this page's canvas: the run's (robots' numbers, marks)."""
        return list(self.base.label_boxes)

    def _robot_points(self, view: SessionView) -> np.ndarray:
        return self._local([r.position for r in view.robots]).reshape(-1, 2)

    def _hidden(self, view: SessionView) -> None:
        """The robots the selected robot cannot see, greyed (a pale disc over their light), and on each
        robot that hides one a small dark square with a thin grey line on to what it hides."""
        where = {i: r.position for i, r in enumerate(view.robots)}
        hidden = self._local([where[j] for j in view.hidden if j in where])
        self._points("/hidden", xyz(hidden, LAYER["fog"]), MARK_COLORS["hidden"], 0.42, "circle")
        pairs = [(where[h], where[j]) for h, j in view.hiders if h in where and j in where]
        hiders = self._local(sorted({a for a, _ in pairs}))
        self._points("/hiders", xyz(hiders, LAYER["fog"]), MARK_COLORS["hider"], 0.2, "square")
        segs = np.zeros((len(pairs), 2, 3), dtype=np.float32)
        if pairs:
            segs[:, 0, :] = xyz(self._local([a for a, _ in pairs]), 0.03)
            segs[:, 1, :] = xyz(self._local([b for _, b in pairs]), 0.03)
        self._segments("/hides", segs, MARK_COLORS["hidden_line"], 1.5)

    def _rays(self, view: SessionView) -> np.ndarray:
        if not view.rays:
            return np.zeros((0, 2, 3))
        a = self._local(np.array(view.rays, dtype=np.int64).reshape(-1, 2)).reshape(-1, 2, 2)
        return np.concatenate([a, np.full((len(a), 2, 1), Z - 0.01, dtype=np.float32)], axis=2)

    # ------------------------------------------------------------------ why: the regions a rule tested
    def _why_regions(self, view: SessionView, taken: list) -> None:
        """The selected robot's regions, translucent so robots stay visible: half planes and bands as
        flat quads, lines as segments, each in its own colour and labelled with the number the Why panel
        gives it. Re-made only when they change (a selection or a decision), so a playing run pays
        nothing for them."""
        regions = view.why.regions if view.why is not None else ()
        key = (regions, tuple(taken))
        if self._last.get("/why") == (key, None, None):
            return
        self._last["/why"] = (key, None, None)
        # Each slot's node is kept and changed in place (a node made anew costs the server its type hints
        # and the browser a new material): what a slot does not show now is hidden.
        shown: set[str] = set()
        labels = []
        for i, mark in enumerate(regions):
            at = self._why_line(i, mark) if isinstance(mark, Line) else None
            if isinstance(mark, HalfPlane | Band):
                at = self._why_area(i, mark)
            shown.add(f"/why/{'line' if isinstance(mark, Line) else 'area'}{i}")
            if at is not None:
                labels.append((f"{i + 1} · {mark.label}", at))
        # Each region's label near where it was put, clear of the run's labels, the ghosts' and each other.
        height, robots = self._text_height(), self._robot_points(view)
        taken = list(taken)
        for k, (text, (x, y, _)) in enumerate(labels):
            step = height + 0.15
            spots = [(x, y + dy, x) for dy in (0.0, -step, step, -2 * step, 2 * step, -3 * step, 3 * step)]
            spot = free_label_spot(spots, robots, text, height, taken)
            taken.append(label_box(text, (spot[0], spot[1], spot[0]), height))
            labels[k] = (text, spot)
        for name in [n for n in self._handles if n.startswith(("/why/area", "/why/line")) and n not in shown]:
            empty = np.zeros((0, 2, 3) if name.startswith("/why/line") else (0, 3), dtype=np.float32)
            self._why_node(name, empty, 0)
        self._labels("/why/labels", labels)

    def _why_line(self, i: int, mark: Line) -> tuple[float, float, float]:
        """A tested line as a segment; its label's place, inside the framed run (the line runs on)."""
        _, _, x1, y1 = self.bounds
        seg = self._line(mark)
        self._why_node(f"/why/line{i}", seg[:1].astype(np.float32), i)
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
        self._why_node(f"/why/area{i}", np.array([(x, y, 0.02) for x, y in corners], dtype=np.float32), i)
        inner = (max(rect[0], x0), max(rect[1], y0), min(rect[2], x1), min(rect[3], y1))
        inside = inner[0] < inner[2] and inner[1] < inner[3]
        return self._region_label_at(mark, inner if inside else rect)

    def _why_node(self, name: str, data: np.ndarray, i: int) -> None:
        """Slot ``i``'s line (segments) or area (a quad's four corners), made once and changed in place;
        hidden when ``data`` is empty."""
        if name.startswith("/why/line"):
            self._segments(name, data, region_color(i), 3.0)
            return
        self._in_place(
            name,
            data,
            lambda: self.scene.add_mesh_simple(
                f"{self.root}{self.prefix}{name}",
                data,
                np.array([(0, 1, 2), (0, 2, 3)], dtype=np.uint32),
                color=region_color(i),
                opacity=REGION_OPACITY,
                material=FULL_CANVAS_MATERIAL,
                side="double",
                cast_shadow=False,
                receive_shadow=False,
            ),
            "vertices",
        )

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


def _selection_inputs(view: SessionView, origin: tuple[int, int], bounds) -> tuple:
    """Everything a selection layer is drawn from: the selected robot and where it is, its rays, ghosts,
    the robots it cannot see and their hiders (and where those are), Why's regions, the lights' colours
    and where the scene is drawn."""
    robots = view.robots
    sel = view.selected
    at = robots[sel].position if sel is not None and sel < len(robots) else None
    fogged = tuple(
        robots[j].position for j in (*view.hidden, *(h for h, _ in view.hiders)) if j < len(robots)
    )
    regions = view.why.regions if view.why is not None else ()
    return (sel, at, view.rays, view.ghosts, view.hidden, view.hiders, fogged, regions, view.legend is None,
            tuple(view.legend), origin, bounds)  # fmt: skip
