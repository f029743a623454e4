"""Cameras: the pose that shows a box of the run whole, how a browser's report is read (its zoom,
its canvas's shape), and a click's ray to a cell."""

from __future__ import annotations

import math

import numpy as np

from apf_viz.ui.scene.labels import TYPICAL_CANVAS_PX
from apf_viz.ui.scene.style import NARROW_ASPECT, NOSE_CELLS, NOSE_MIN_PX, RIM_PLAYING_PX, Bounds


def _unskipped(held, wanted):
    """``wanted``, or a hair off it when it equals what viser holds for the browser's camera: viser drops
    a value equal to the one it holds, and what it holds may be the browser's late report while the page
    is still on its way to an earlier pose (sent B, reported A, sent A: dropped, and the page came to
    rest at B). The hair is 1e-4 of the last coordinate (the camera's height; a scalar's size), past
    viser's 1e-5 and far inside what counts as the same pose (``browser_screen._same_pose``, 1e-3 of
    the height)."""
    held_, wanted_ = np.asarray(held, dtype=float), np.array(wanted, dtype=float)
    if not np.allclose(held_, wanted_):
        return wanted
    last = wanted_.reshape(-1)
    last[-1] += 1e-4 * max(abs(last[-1]), 1.0)
    return float(wanted_) if wanted_.ndim == 0 else tuple(float(v) for v in wanted_)


GROWTH_ROOM = 0.2
"""Of the run's extent: the room a camera re-framed for a growing run leaves beyond each side it grew."""


def grown_box(box: Bounds, framed: Bounds) -> Bounds:
    """What a camera shows when the run (``box``) has grown out of the ``framed`` box: both, with room
    beyond each side that grew. A run that grows a cell at a time (the line reaching out from the leader,
    a robot walking away) then moves the camera every few cells, not at every frame: a steadier picture,
    and no camera messages in the frames between."""
    room = GROWTH_ROOM * max(box[2] - box[0], box[3] - box[1], 5.0)
    return (
        box[0] - room if box[0] < framed[0] else framed[0],
        box[1] - room if box[1] < framed[1] else framed[1],
        box[2] + room if box[2] > framed[2] else framed[2],
        box[3] + room if box[3] > framed[3] else framed[3],
    )


def scene_detail(visible_height: float) -> tuple[bool, bool]:
    """What is drawn of the robots when the canvas shows ``visible_height`` cells: (the y-axis
    diamonds, wide enough on screen to be seen; the outlines even while playing, a cell at least
    ``RIM_PLAYING_PX`` wide)."""
    cell_px = TYPICAL_CANVAS_PX / max(visible_height, 1e-9)
    return NOSE_CELLS * cell_px >= NOSE_MIN_PX, cell_px >= RIM_PLAYING_PX


def camera_cells(camera) -> float | None:
    """How many cells tall a browser's camera shows at the grid (None before it has reported)."""
    try:
        position = np.asarray(camera.position, dtype=float)
        look_at = np.asarray(camera.look_at, dtype=float)
        fov = float(camera.fov)
    except (AssertionError, TypeError, ValueError):
        return None
    return 2.0 * float(np.linalg.norm(position - look_at)) * float(np.tan(fov / 2))


def ray_through(camera, screen: tuple[float, float]) -> tuple[np.ndarray, np.ndarray]:
    """The ray from a browser's camera through a point of its canvas (``screen``: 0..1 each way, from
    the top-left, as viser reports a dragged box), in scene coordinates."""
    p = np.asarray(camera.position, dtype=float)
    forward = np.asarray(camera.look_at, dtype=float) - p
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    t = np.tan(float(camera.fov) / 2)
    x, y = 2 * screen[0] - 1, 1 - 2 * screen[1]
    return p, forward + x * t * camera_aspect(camera) * right + y * t * up


def camera_aspect(camera) -> float:
    """The width / height of a browser's canvas, as its camera reports it (before it has: the narrow
    canvas new browsers are framed for)."""
    try:
        aspect = float(camera.aspect)
    except (AssertionError, AttributeError, TypeError, ValueError):
        return NARROW_ASPECT
    return aspect if aspect == aspect and aspect > 0 else NARROW_ASPECT


def cell_of_ray(origin, direction) -> tuple[int, int] | None:
    """The grid cell a click ray hits on the plane z = 0 (robots are small, so the cell is enough)."""
    point = point_of_ray(origin, direction)
    return None if point is None else (round(point[0]), round(point[1]))


def covered_cells(a: tuple[float, float], b: tuple[float, float]) -> tuple[tuple[int, int], tuple[int, int]]:
    """The box a drag from ``a`` to ``b`` draws: from the cell the press was in to the cell the release
    was in, both included (as a pixel editor's rectangle: a release short of the last cell's centre
    still takes that cell)."""
    (x0, x1), (y0, y1) = sorted((round(a[0]), round(b[0]))), sorted((round(a[1]), round(b[1])))
    return (x0, y0), (x1, y1)


def point_of_ray(origin, direction) -> tuple[float, float] | None:
    """Where a ray hits the plane z = 0 (None: it does not, or a browser sent a ray of no numbers)."""
    ox, oy, oz = origin
    dx, dy, dz = direction
    if abs(dz) < 1e-9:
        return None
    t = -oz / dz
    if t < 0:
        return None
    x, y = ox + t * dx, oy + t * dy
    if not (math.isfinite(x) and math.isfinite(y)):
        return None  # a browser may send any ray
    return (x, y)


def pose_for(
    bounds: Bounds, aspect: float = NARROW_ASPECT, caption_room: float = 0.0
) -> tuple[tuple[float, float, float], tuple[float, float, float], float]:
    """(position, look_at, fov) of a top-down view of ``bounds`` (x0, y0, x1, y1, scene units), for a
    canvas ``aspect`` = width / height (the field of view is vertical, so a narrow canvas needs the
    camera higher to fit the run's width); ``caption_room``: the share of the canvas's height to leave
    free at the bottom (presentation mode's caption floats there, clear of the notifications, which the
    page shows at the top left)."""
    x0, y0, x1, y1 = bounds
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
    fov = float(np.deg2rad(50))
    extent = max((y1 - y0 + 4) / (1 - caption_room), (x1 - x0 + 4) / max(aspect, 0.2), 10)
    cy -= caption_room * extent / 2  # the run in the middle of the canvas's upper part
    h = extent / (2 * np.tan(fov / 2))
    # A little south of straight above: the orbit controls need a direction that is not "up".
    return (cx, cy - 0.05 * h, h), (cx, cy, 0.0), fov
