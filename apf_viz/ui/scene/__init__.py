"""The only package that touches a viser scene: draws a :class:`SessionView`, one atomic update a frame;
the run in the scene every browser shares, each browser's selection in that browser's own scene.

Robots are flat, unlit discs in their light's legend colour (one point cloud per light) on a dark
outline (left out while a crowd framed whole plays: ``RIM_CROWD``), with a small diamond on each robot's
+y side for its y-axis (the adversary's flip); its phase, the last actor and the selection are rings:
wider discs under it. One vertex per robot and ring, because
in a browser without a GPU every instance of a batched mesh or line set costs about as much as a draw
call of its own. Up to ``DENSE`` robots a pending move is a line segment, above it a red dot on the cell
it goes to. Target cells are flat squares; rays, K, the leader's frame and the grid are line-segment
sets, the grid's density chosen by :func:`grid_steps`. Every node is created once and then updated in
place, hidden when empty: a node re-created gets a new material, and a software-rendered browser
compiles its shader again. docs/PERFORMANCE.md has the measurements.

The package's rooms: ``style`` (sizes, layers), ``canvas`` (the primitives and their state), ``robots``,
``grid``, ``marks`` (what the algorithm describes), ``selection`` (one browser's), ``labels`` (where text
goes), ``camera`` and ``framing`` (poses, and the browsers' cameras), ``renderer`` (a frame, layer by
layer).
"""

from apf_viz.ui.scene.camera import (
    GROWTH_ROOM,
    camera_aspect,
    camera_cells,
    cell_of_ray,
    grown_box,
    pose_for,
    ray_through,
    scene_detail,
)
from apf_viz.ui.scene.grid import grid_steps
from apf_viz.ui.scene.labels import (
    cells_label_at,
    frame_label_at,
    free_label_spot,
    label_box,
    number_labels,
    text_cells,
)
from apf_viz.ui.scene.renderer import SceneRenderer
from apf_viz.ui.scene.style import (
    DENSE,
    GRID_CELL_PX,
    GRID_SECTION_PX,
    NARROW_ASPECT,
    STALE_MARK,
    VIEW_PX,
    Bounds,
    light_colors,
)

__all__ = [
    "DENSE",
    "GRID_CELL_PX",
    "GRID_SECTION_PX",
    "GROWTH_ROOM",
    "NARROW_ASPECT",
    "STALE_MARK",
    "VIEW_PX",
    "Bounds",
    "SceneRenderer",
    "camera_aspect",
    "camera_cells",
    "cell_of_ray",
    "cells_label_at",
    "frame_label_at",
    "free_label_spot",
    "grid_steps",
    "grown_box",
    "label_box",
    "light_colors",
    "number_labels",
    "pose_for",
    "ray_through",
    "scene_detail",
    "text_cells",
]
