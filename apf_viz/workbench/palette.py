"""The colours of every mark the screen draws, in one table: the scene draws with them and the legend
shows the same swatches (an algorithm's lights bring their own colours, core/portrayal.py)."""

from __future__ import annotations

from typing import Literal

PointShape = Literal["square", "circle", "diamond", "sparkle"]
"""The shapes viser draws a point cloud's points in."""

Color = tuple[int, int, int]

PHASE_COLORS: dict[str, Color] = {
    "idle": (238, 238, 238),
    "looked": (250, 210, 40),
    "computed": (250, 120, 30),
}
TARGET_COLORS: dict[str, Color] = {
    "placed": (100, 205, 100),
    "preview": (160, 220, 160),
    "drawing": (240, 120, 190),
}
# The engine's marks, one colour each. Chosen with the lights (Okabe & Ito's colour-blind-safe set) so
# that the marks of a failure picture stay apart for every viewer: leader (vermillion disc), collision
# (magenta burst), selected (black ring) and "will never act" (grey square) differ in colour under
# simulated protan-, deutan- and tritanopia and in shape (tests/test_palette.py). A pending move is
# magenta like the collision it may become.
MARK_COLORS: dict[str, Color] = {
    "ray": (250, 200, 0),
    "ghost": (110, 110, 110),
    "hidden": (236, 236, 236),  # the pale disc over a robot the selected one cannot see
    "hider": (40, 40, 40),
    "hidden_line": (170, 170, 170),
    "never": (120, 120, 120),
    "outline": (50, 50, 50),
    "pending": (150, 0, 110),
    "axis": (190, 0, 190),
    "collision": (190, 0, 190),
    "last": (140, 90, 40),  # brown and black: no light of the paper's legend is either
    "selected": (0, 0, 0),
    "diverged": (86, 180, 233),  # Compare: the robot whose event first differs, a diamond in both runs
    "region": (0, 114, 178),  # the first of REGION_COLORS: the legend's swatch
    "line": (90, 90, 90),  # an algorithm's line or frame that names no colour of its own
    "frame": (30, 30, 30),
    "anchor": (213, 94, 0),  # Edit: the first click of a two-click tool, waiting for the second
    "named": (0, 158, 115),  # a figure: the robot its caption names (r, r₀) and the lines named by it
}
# The regions a Why explanation tested, each its own colour (in order: the rule's first test first), so
# that "1" on the canvas and "1" in the panel are the same region at a glance. Okabe & Ito again.
REGION_COLORS: tuple[Color, ...] = (
    (0, 114, 178),
    (230, 159, 0),
    (0, 158, 115),
    (204, 121, 167),
    (86, 180, 233),
    (213, 94, 0),
)


def region_color(i: int) -> Color:
    """The colour of the i-th region Why shows (0-based)."""
    return REGION_COLORS[i % len(REGION_COLORS)]


# The shape each of those marks is drawn in (viser's point shapes), so that shape alone tells them apart.
MARK_SHAPES: dict[str, PointShape] = {
    "collision": "sparkle",
    "never": "square",
    "selected": "circle",
    "last": "circle",
    "anchor": "diamond",
}
