"""A figure's content, in grid units, read off a view: what the canvas shows, and nothing of viser."""

from __future__ import annotations

from dataclasses import dataclass, field

from apf_viz.core.portrayal import Cells, Frame, Line
from apf_viz.lecture import Marked
from apf_viz.workbench.palette import MARK_COLORS, TARGET_COLORS
from apf_viz.workbench.view_model import SessionView

RGB = tuple[int, int, int]
MARGIN = 2.0  # cells of grid beyond the outermost robot, target or frame arm (room for its number)


@dataclass(frozen=True)
class Disc:
    """A robot: where, its number and light (the legend's name), and its light's colour."""

    at: tuple[int, int]
    number: int
    light: str
    color: RGB
    square: bool = False  # its light is drawn as a square (LightStyle.shape), not a disc


@dataclass(frozen=True)
class Drawing:
    """Everything a figure draws, in grid coordinates; ``box`` (x0, y0, x1, y1) is the grid shown."""

    box: tuple[float, float, float, float]
    cells: tuple[tuple[int, int], ...]
    cells_color: RGB
    cells_label: str
    robots: tuple[Disc, ...]
    lines: tuple[tuple[str, float, str, RGB], ...]  # (axis, at, label, colour): x = at or y = at
    frames: tuple[tuple[tuple[int, int], int, str, RGB], ...]  # (origin, y sign, label, colour)
    rays: tuple[tuple[tuple[int, int], tuple[int, int]], ...] = ()
    hidden: tuple[tuple[int, int], ...] = ()  # where the robots the selected one cannot see are
    selected: tuple[int, int] | None = None
    legend: tuple[tuple[str, RGB], ...] = ()  # the lights shown, in the algorithm's order
    square_lights: tuple[str, ...] = ()  # those of them drawn as squares
    marks_legend: tuple[tuple[str, RGB], ...] = field(default=())  # the marks shown: (name, colour)
    caption: str = ""
    named: tuple[tuple[tuple[int, int], str], ...] = ()  # robots the caption names: (where, "r")


def drawing_of(view: SessionView, caption: str = "", marked: Marked | None = None) -> Drawing:
    """The figure of ``view``: its robots, the algorithm's targets, lines and frames, the selected
    robot's rays (to what it saw) and the robots it cannot see; ``marked``: the robot a paper's caption
    names, and the lines it names by it (``L_I(r)``), drawn and labelled."""
    robots = tuple(
        Disc(
            r.position,
            i,
            r.light,
            view.legend[r.light].color if r.light in view.legend else (0, 0, 0),
            r.light in view.legend and view.legend[r.light].shape == "square",
        )
        for i, r in enumerate(view.robots)
    )
    cells = next((m for m in view.overlays.marks if isinstance(m, Cells)), None)
    targets = cells.points if cells is not None else tuple(view.targets)
    style = cells.style if cells is not None else "placed"
    lines: tuple[tuple[str, float, str, RGB], ...] = tuple(
        (str(m.axis), float(m.at), m.label, m.color or MARK_COLORS["line"])
        for m in view.overlays.marks
        if isinstance(m, Line)
    )
    frames = tuple(
        (m.origin, m.y_sign, m.label, m.color or MARK_COLORS["frame"])
        for m in view.overlays.marks
        if isinstance(m, Frame)
    )
    named: tuple[tuple[tuple[int, int], str], ...] = ()
    if marked is not None and marked.robot < len(view.robots):
        named = ((view.robots[marked.robot].position, marked.name),)
        lines += named_lines([r.position for r in view.robots], marked)
    sel = view.selected
    selected = view.robots[sel].position if sel is not None and sel < len(view.robots) else None
    hidden = tuple(view.robots[j].position for j in view.hidden if j < len(view.robots))
    rays = tuple((tuple(a), tuple(b)) for a, b in view.rays) if selected is not None else ()
    shown = {d.light for d in robots}
    legend = tuple((light, style_.color) for light, style_ in view.legend.items() if light in shown)
    marks: list[tuple[str, RGB]] = []
    if targets:
        marks.append((cells.label if cells is not None else "targets", TARGET_COLORS[style]))
    if rays:
        marks.append(("what the selected robot saw", MARK_COLORS["ray"]))
    if hidden:
        marks.append(("hidden from it", MARK_COLORS["hidden_line"]))
    return Drawing(
        box=_box([d.at for d in robots] + list(targets), lines, frames),
        cells=tuple(targets),
        cells_color=TARGET_COLORS[style],
        cells_label=cells.label if cells is not None else "targets",
        robots=robots,
        lines=lines,
        frames=frames,
        rays=rays,  # type: ignore[arg-type]
        hidden=hidden,
        selected=selected,
        legend=legend,
        square_lights=tuple(light for light, _ in legend if view.legend[light].shape == "square"),
        marks_legend=tuple(marks),
        caption=caption,
        named=named,
    )


def named_lines(points: list[tuple[int, int]], marked: Marked) -> tuple[tuple[str, float, str, RGB], ...]:
    """The lines a caption names by a robot, as the paper defines them: ``L_V(r)`` and ``L_H(r)`` through
    it, ``L_I(r)`` and ``R_I(r)`` the nearest occupied vertical lines to its left and right (none where
    no robot stands on that side)."""
    x, y = points[marked.robot]
    left = [p[0] for p in points if p[0] < x]
    right = [p[0] for p in points if p[0] > x]
    at = {"L_V": ("x", x), "L_H": ("y", y), "L_I": ("x", max(left, default=None)),
          "R_I": ("x", min(right, default=None))}  # fmt: skip
    color = MARK_COLORS["named"]
    return tuple(
        (axis, float(where), f"{name}({marked.name})", color)
        for name in marked.lines
        for axis, where in [at[name]]
        if where is not None
    )


def _box(points, lines, frames) -> tuple[float, float, float, float]:
    xs = [p[0] for p in points] + [o[0] + dx for o, _, _, _ in frames for dx in (0, 2)]
    ys = [p[1] for p in points] + [o[1] + 2 * s for o, s, _, _ in frames] + [o[1] for o, _, _, _ in frames]
    if not xs:
        xs, ys = [0], [0]
    return (min(xs) - MARGIN, min(ys) - MARGIN, max(xs) + MARGIN, max(ys) + MARGIN)
