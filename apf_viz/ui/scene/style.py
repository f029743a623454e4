"""How the scene looks: sizes, layers (the height of each kind of disc), densities, and the
scene's units."""

from __future__ import annotations

import numpy as np

from apf_viz.workbench.view_model import SessionView

ROBOT_RADIUS = 0.3
# Grid density, for a run framed about VIEW_PX pixels wide: a line per cell while a cell is at least
# GRID_CELL_PX wide, and darker section lines every 5, 10, 50, ... cells, at least GRID_SECTION_PX apart.
VIEW_PX = 1000
GRID_CELL_PX = 20
GRID_SECTION_PX = 45
SECTION_STEPS = (5, 10, 50, 100, 500, 1000, 5000, 10000)
# Above this many robots, robots, y-axes and pending moves are point sprites, one vertex each, not
# instanced meshes and line segments: in a software-rendered browser each instance costs about 0.2 ms a
# frame, as much as a draw call (measured, docs/PERFORMANCE.md).
DENSE = 50
# viser draws a point of size s as a square 2·s world units wide (its scale divides by tan(fov/2), where
# the frustum's height is 2·tan(fov/2)·z); sizes here are world widths.
VISER_POINT_SCALE = 0.5
# Robots and their rings are flat discs in layers just above the grid, far enough apart for the depth
# buffer (about 0.006 units at a typical camera distance) and close enough that perspective does not
# shift one against another. Flat and unlit: a light's colour on the canvas is its legend swatch.
Bounds = tuple[float, float, float, float]  # (x0, y0, x1, y1) in scene units: a run's box, a label's
Z = 0.12  # the robots' discs
LAYER = {
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
SIZE = {  # disc diameters in cells: each ring shows as the band between its disc and the next
    "selected": 1.22,
    "never": 1.1,
    "last": 1.02,
    "phase": 0.88,
    "outline": 2 * ROBOT_RADIUS + 0.1,
    "robot": 2 * ROBOT_RADIUS,
}


def light_colors(view: SessionView) -> dict[str, tuple[int, int, int]]:
    """Each light's colour, from the algorithm's legend (core/portrayal.py gives every light one)."""
    return {light: style.color for light, style in view.legend.items()}


LABEL_ROOM = 4.0  # cells right of two runs compared, for the labels of the one on the right
REGION_OPACITY = 0.13
FULL_CANVAS_MATERIAL = "toon3"
"""The material of a surface that may fill much of the canvas (a region's shading, the paint surface):
not viser's lit default, whose every pixel costs a physically based lighting pass. In software GL (a
projector laptop, Chromium without a GPU) a canvas-wide lit quad cost 300-480 ms a frame and a 7-8 s
stall when first shown (docs/PERFORMANCE.md)."""
# The canvas a new browser is framed for before it reports its own: 1024×768 with the panel docked
# (about 640×768). A wider canvas then shows a margin; a narrower guess would cut a 1024 projector's view.
NARROW_ASPECT = 0.83
# viser's em is 12 px at 1: robot numbers at 18 px, near the caption's words (WORDS_PX, 20 px), so that the
# back row reads them (at 14.4 px they were 7 px in a projector's picture at half size; the words 10 px).
LABEL_SCALE = 1.5


def xyz(points, z: float) -> np.ndarray:
    arr = np.asarray(points, dtype=np.float32).reshape(-1, 2)
    return np.column_stack([arr, np.full(len(arr), z, dtype=np.float32)])


# The browser draws in float32, exact for integers only below 2^24 and smooth only well below: the scene is
# drawn relative to an integer origin near the run, moved when the run is farther than this from it.
REORIGIN_DISTANCE = 1 << 20
