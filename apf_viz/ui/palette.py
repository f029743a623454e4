"""The colours of every mark the screen draws, in one table: the scene draws with them and the legend
shows the same swatches (an algorithm's lights bring their own colours, core/portrayal.py)."""

from __future__ import annotations

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
    "never": (120, 120, 120),
    "outline": (50, 50, 50),
    "pending": (150, 0, 110),
    "axis": (190, 0, 190),
    "collision": (190, 0, 190),
    "last": (140, 90, 40),  # brown and black: no light of the paper's legend is either
    "selected": (0, 0, 0),
    "region": (40, 120, 255),
    "line": (90, 90, 90),  # an algorithm's line or frame that names no colour of its own
    "frame": (30, 30, 30),
}
# The shape each of those marks is drawn in (viser's point shapes), so that shape alone tells them apart.
MARK_SHAPES: dict[str, str] = {
    "collision": "sparkle",
    "never": "square",
    "selected": "circle",
    "last": "circle",
}
