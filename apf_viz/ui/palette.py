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
# The engine's marks, one colour each.
MARK_COLORS: dict[str, Color] = {
    "ray": (250, 200, 0),
    "ghost": (120, 60, 200),
    "never": (150, 0, 0),
    "outline": (50, 50, 50),
    "pending": (230, 40, 40),
    "axis": (255, 0, 0),
    "collision": (230, 0, 0),
    "last": (140, 90, 40),  # brown and black: no light of the paper's legend is either
    "selected": (0, 0, 0),
    "region": (40, 120, 255),
    "line": (90, 90, 90),  # an algorithm's line or frame that names no colour of its own
    "frame": (30, 30, 30),
}
