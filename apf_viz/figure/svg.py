"""A drawing as an SVG document: one cell is :data:`CELL` pixels, y up as in the paper, a legend on the
right and the caption under it."""

from __future__ import annotations

import math
import textwrap
from html import escape

from apf_viz.figure.drawing import RGB, Drawing
from apf_viz.workbench.palette import MARK_COLORS
from apf_viz.workbench.view_model.legend import canvas_symbol

CELL = 24.0
LEGEND_WIDTH = 190.0
ROBOT_R = 0.34  # a robot's disc, in cells
NUMBER_PX = 14  # a robot's number: over half a cell, read at the size a paper prints a figure


def _rgb(c: RGB) -> str:
    return f"rgb({c[0]},{c[1]},{c[2]})"


def _el(tag: str, **attrs) -> str:
    """An empty element; ``stroke_width`` is written ``stroke-width`` (any ``_`` becomes ``-``)."""
    body = " ".join(
        f'{k.replace("_", "-")}="{round(v, 2) if isinstance(v, float) else v}"' for k, v in attrs.items()
    )
    return f"<{tag} {body}/>"


def _text(x: float, y: float, text: str, anchor: str = "start", size: int = 11) -> str:
    return f'<text x="{x:.2f}" y="{y:.2f}" font-size="{size}" text-anchor="{anchor}">{escape(text)}</text>'


class _Page:
    """The drawing's grid box mapped onto the page (y flipped: up in the paper is up on the page)."""

    def __init__(self, d: Drawing) -> None:
        self.x0, self.y0, self.x1, self.y1 = d.box
        self.width, self.height = (self.x1 - self.x0) * CELL, (self.y1 - self.y0) * CELL

    def x(self, x: float) -> float:
        return (x - self.x0) * CELL

    def y(self, y: float) -> float:
        return (self.y1 - y) * CELL


def to_svg(d: Drawing) -> str:
    p = _Page(d)
    rows = 1 + len(d.legend) + len(d.marks_legend)
    total_w = p.width + LEGEND_WIDTH
    caption = textwrap.wrap(d.caption, max(20, int(total_w / 6.6)))  # about 6.6 px a character at 12 px
    top = max(p.height, 18 * rows + 10)
    total_h = top + (16 * len(caption) + 10 if caption else 0)
    out = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{total_w:.0f}" height="{total_h:.0f}" '
        f'viewBox="0 0 {total_w:.2f} {total_h:.2f}" font-family="Helvetica, Arial, sans-serif">',
        _el("rect", width=total_w, height=total_h, fill="white"),
        *_grid(p),
        *_marks(d, p),
        *_robots(d, p),
        *_legend(d, p.width + 14),
    ]
    out += [_text(4, top + 18 + 16 * i, line, size=12) for i, line in enumerate(caption)]
    out.append("</svg>")
    return "\n".join(out) + "\n"


def _grid(p: _Page) -> list[str]:
    """A line between every two cells (cells are centred on integer points)."""
    xs = [k + 0.5 for k in range(math.floor(p.x0), math.ceil(p.x1))]
    ys = [k + 0.5 for k in range(math.floor(p.y0), math.ceil(p.y1))]
    lines = [_el("line", x1=p.x(x), y1=0.0, x2=p.x(x), y2=p.height) for x in xs]
    lines += [_el("line", x1=0.0, y1=p.y(y), x2=p.width, y2=p.y(y)) for y in ys]
    return [f'<g stroke="rgb(225,225,225)" stroke-width="1">{"".join(lines)}</g>']


def _marks(d: Drawing, p: _Page) -> list[str]:
    """Target cells, the algorithm's lines and frames, and the selected robot's rays."""
    half = 0.4 * CELL
    out = [
        _el(
            "rect",
            x=p.x(x) - half,
            y=p.y(y) - half,
            width=2 * half,
            height=2 * half,
            fill=_rgb(d.cells_color),
        )
        for x, y in d.cells
    ]
    for axis, at, label, color in d.lines:
        if axis == "x":
            out.append(
                _el("line", x1=p.x(at), y1=0.0, x2=p.x(at), y2=p.height, stroke=_rgb(color), stroke_width=2.5)
            )
            out.append(_text(p.x(at) + 4, 12, canvas_symbol(label)))
        else:
            out.append(
                _el("line", x1=0.0, y1=p.y(at), x2=p.width, y2=p.y(at), stroke=_rgb(color), stroke_width=2.5)
            )
            out.append(_text(p.width - 4, p.y(at) - 4, canvas_symbol(label), "end"))
    for (ox, oy), s, label, color in d.frames:
        corner, arm_x, arm_y = (p.x(ox), p.y(oy)), p.x(ox + 2), p.y(oy + 2 * s)
        path = f"M{arm_x:.2f},{corner[1]:.2f} L{corner[0]:.2f},{corner[1]:.2f} L{corner[0]:.2f},{arm_y:.2f}"
        out.append(_el("path", d=path, fill="none", stroke=_rgb(color), stroke_width=2.5))
        out.append(_text(arm_x + 4, corner[1] + 4, label))  # beyond the x arm, clear of the robot there
    ray = _rgb(MARK_COLORS["ray"])
    out += [
        _el("line", x1=p.x(a[0]), y1=p.y(a[1]), x2=p.x(b[0]), y2=p.y(b[1]), stroke=ray, stroke_width=2.0)
        for a, b in d.rays
    ]
    return out


def _robots(d: Drawing, p: _Page) -> list[str]:
    """Each robot a disc in its light's colour with its number; those the selected one cannot see
    veiled; the selected one ringed."""
    r = ROBOT_R * CELL
    outline = _rgb(MARK_COLORS["outline"])
    out = []
    for disc in d.robots:
        x, y = p.x(disc.at[0]), p.y(disc.at[1])
        fill = _rgb(disc.color)
        if disc.square:
            box = {"x": x - r, "y": y - r, "width": 2 * r, "height": 2 * r}
            out.append(_el("rect", **box, fill=fill, stroke=outline, stroke_width=1.5))
        else:
            out.append(_el("circle", cx=x, cy=y, r=r, fill=fill, stroke=outline, stroke_width=1.5))
        out.append(_text(x + r, y - r, str(disc.number), size=NUMBER_PX))
    named = _rgb(MARK_COLORS["named"])
    for (nx, ny), name in d.named:  # the robot the caption names: ringed, its name at its lower left
        x, y = p.x(nx), p.y(ny)
        out.append(_el("circle", cx=x, cy=y, r=r + 5, fill="none", stroke=named, stroke_width=2.5))
        out.append(
            f'<text x="{x - r - 6:.2f}" y="{y + r + 15:.2f}" font-size="16" font-weight="bold" '
            f'font-style="italic" fill="{named}" text-anchor="end">{escape(name)}</text>'
        )
    veil, edge = _rgb(MARK_COLORS["hidden"]), _rgb(MARK_COLORS["hidden_line"])
    out += [
        _el(
            "circle",
            cx=p.x(x),
            cy=p.y(y),
            r=r,
            fill=veil,
            fill_opacity=0.8,
            stroke=edge,
            stroke_dasharray="3,2",
        )
        for x, y in d.hidden
    ]
    if d.selected is not None:
        sel = d.selected
        out.append(
            _el(
                "circle", cx=p.x(sel[0]), cy=p.y(sel[1]), r=r + 4, fill="none", stroke="black", stroke_width=2
            )
        )
    return out


def _legend(d: Drawing, left: float) -> list[str]:
    out, y = [], 18.0
    for name, color in d.legend:
        if name in d.square_lights:
            out.append(
                _el("rect", x=left, y=y - 10, width=12, height=12, fill=_rgb(color), stroke="rgb(50,50,50)")
            )
        else:
            out.append(_el("circle", cx=left + 6, cy=y - 4, r=6, fill=_rgb(color), stroke="rgb(50,50,50)"))
        out.append(_text(left + 18, y, name))
        y += 18
    for name, color in d.marks_legend:
        out.append(_el("rect", x=left, y=y - 10, width=12, height=12, fill=_rgb(color)))
        out.append(_text(left + 18, y, name))
        y += 18
    return out
