"""A drawing as a PNG, with matplotlib (the ``sweep`` extra): the same picture as the SVG, rasterised."""

from __future__ import annotations

import io
import math

from apf_viz.figure.drawing import RGB, Drawing
from apf_viz.workbench.palette import MARK_COLORS

DPI = 150
CELL_INCHES = 0.25


def _c(rgb: RGB) -> tuple[float, float, float]:
    return (rgb[0] / 255, rgb[1] / 255, rgb[2] / 255)


def to_png(d: Drawing) -> bytes:
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib import pyplot as plt
    from matplotlib.patches import Circle, Patch, Rectangle

    x0, y0, x1, y1 = d.box
    fig, ax = plt.subplots(figsize=((x1 - x0) * CELL_INCHES + 2.6, (y1 - y0) * CELL_INCHES + 0.6), dpi=DPI)
    try:
        ax.set_xlim(x0, x1)
        ax.set_ylim(y0, y1)
        ax.set_aspect("equal")
        ax.axis("off")
        for k in range(math.floor(x0), math.ceil(x1)):
            ax.axvline(k + 0.5, color=(0.88, 0.88, 0.88), lw=0.5, zorder=0)
        for k in range(math.floor(y0), math.ceil(y1)):
            ax.axhline(k + 0.5, color=(0.88, 0.88, 0.88), lw=0.5, zorder=0)
        for x, y in d.cells:
            ax.add_patch(Rectangle((x - 0.4, y - 0.4), 0.8, 0.8, color=_c(d.cells_color), zorder=1))
        for axis, at, label, color in d.lines:
            (ax.axvline if axis == "x" else ax.axhline)(at, color=_c(color), lw=2, zorder=2)
            ax.annotate(label, (at, y1) if axis == "x" else (x1, at), fontsize=7, ha="right", va="bottom")
        for (ox, oy), s, label, color in d.frames:
            ax.plot([ox + 2, ox, ox], [oy, oy, oy + 2 * s], color=_c(color), lw=2, zorder=2)
            ax.annotate(label, (ox + 2.1, oy), fontsize=7, va="center")
        for a, b in d.rays:
            ax.plot([a[0], b[0]], [a[1], b[1]], color=_c(MARK_COLORS["ray"]), lw=1.2, zorder=3)
        _robots(ax, d)
        handles: list[Patch] = [
            Rectangle((0, 0), 1, 1, color=_c(c), label=name) if name in d.square_lights
            else Circle((0, 0), 1, color=_c(c), label=name)
            for name, c in d.legend
        ]  # fmt: skip
        handles += [Rectangle((0, 0), 1, 1, color=_c(c), label=name) for name, c in d.marks_legend]
        if handles:
            ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1), fontsize=7, frameon=False)
        if d.caption:
            fig.text(0.01, 0.01, d.caption, fontsize=7, wrap=True)
        out = io.BytesIO()
        fig.savefig(out, format="png", bbox_inches="tight")
        return out.getvalue()
    finally:
        plt.close(fig)


def _robots(ax, d: Drawing) -> None:
    """Each robot in its light's colour and shape with its number; the robot a caption names ringed
    and named; those the selected one cannot see veiled; the selected one ringed."""
    from matplotlib.patches import Circle, Rectangle

    for disc in d.robots:
        edge = _c(MARK_COLORS["outline"])
        ax.add_patch(
            Rectangle((disc.at[0] - 0.34, disc.at[1] - 0.34), 0.68, 0.68, facecolor=_c(disc.color),
                      edgecolor=edge, zorder=4)
            if disc.square
            else Circle(disc.at, 0.34, facecolor=_c(disc.color), edgecolor=edge, zorder=4)
        )  # fmt: skip
        ax.annotate(str(disc.number), (disc.at[0] + 0.35, disc.at[1] + 0.35), fontsize=8, zorder=5)
    named = _c(MARK_COLORS["named"])
    for (x, y), name in d.named:  # the robot the caption names: ringed, its name at its lower left
        ax.add_patch(Circle((x, y), 0.5, fill=False, edgecolor=named, lw=1.8, zorder=6))
        ax.annotate(
            name, (x - 0.55, y - 0.55), fontsize=10, fontweight="bold", color=named, ha="right", va="top"
        )
    for x, y in d.hidden:
        ax.add_patch(Circle((x, y), 0.34, facecolor=_c(MARK_COLORS["hidden"]), alpha=0.8, ls="--", zorder=5))
    if d.selected is not None:
        ax.add_patch(Circle(d.selected, 0.5, fill=False, edgecolor="black", lw=1.5, zorder=6))
