"""The lattice geometry watches are made of: a segment's points, boxes in the global frame, the nearest
robot along a direction. Exact integer arithmetic."""

from __future__ import annotations

from collections.abc import Sequence
from math import gcd

import numpy as np

from apf_viz.core.algorithm import Box
from apf_viz.core.grid import Point

BIG = 1 << 62  # beyond every coordinate (COORD_LIMIT): an unbounded side of a box
VECTOR_SPAN = 1 << 30  # offsets below this: products of two fit in int64


MAX_LISTED = 4096
"""The most lattice points a segment is listed by; callers keep longer ones by direction and length."""


def lattice_points(x: int, y: int, dx: int, dy: int) -> list[Point]:
    """The lattice points of the segment from (x, y) to (x + dx, y + dy), without (x, y) itself: nothing
    moves onto a watching robot."""
    g = gcd(dx, dy)
    if g > MAX_LISTED:  # a list that grows with a distance: the caller was to keep the segment whole
        raise ValueError(f"a segment of {g:,} lattice points is not listed (at most {MAX_LISTED:,})")
    ux, uy = dx // g, dy // g
    return [(x + t * ux, y + t * uy) for t in range(1, g + 1)]


def nearest_along(P: np.ndarray, q: int, ux: int, uy: int) -> tuple[int, int]:
    """The robot nearest to robot q along the primitive direction (ux, uy), and its distance in lattice
    steps; (−1, 0) if there is none. Products of a direction and a gcd only: nothing can overflow."""
    ox = P[:, 0] - P[q, 0]
    oy = P[:, 1] - P[q, 1]
    g = np.gcd(ox, oy)
    on = ((ox == ux * g) & (oy == uy * g) & (g > 0)).nonzero()[0]
    if not on.size:
        return -1, 0
    i = int(on[np.argmin(g[on])])
    return i, int(g[i])


def touches(
    P: np.ndarray,
    r: int,
    boxes: list[tuple[int, int, int, int]],
    longs: list[tuple[int, int, int]],
    points: Sequence[Point],
) -> bool:
    """Whether one of these points lies in one of robot r's boxes or long segments (global frame)."""
    for px, py in points:
        for x0, x1, y0, y1 in boxes:
            if x0 <= px <= x1 and y0 <= py <= y1:
                return True
        if longs:
            dx, dy = px - int(P[r, 0]), py - int(P[r, 1])
            g = gcd(dx, dy)
            if g and any(dx == ux * g and dy == uy * g and g <= length for ux, uy, length in longs):
                return True
    return False


def inside(p: Point, box: tuple[int, int, int, int] | None) -> bool:
    """Whether ``p`` lies in ``box`` (x0, x1, y0, y1, bounds included); a box of None holds every point."""
    return box is None or (box[0] <= p[0] <= box[1] and box[2] <= p[1] <= box[3])


def global_box(x: int, y: int, s: int, box: Box) -> tuple[int, int, int, int]:
    """A box of the robot at (x, y) whose local +y is the global s·y, as global bounds (±2^62 for None)."""
    x0, x1, y0, y1 = box
    if s == -1:  # the robot's +y is the global −y: its box flips about its own row
        y0, y1 = (None if y1 is None else -y1), (None if y0 is None else -y0)
    return (
        -BIG if x0 is None else x + x0,
        BIG if x1 is None else x + x1,
        -BIG if y0 is None else y + y0,
        BIG if y1 is None else y + y1,
    )


def robots_in(P: np.ndarray, box: tuple[int, int, int, int], r: int) -> int:
    """How many robots (``P``: their points) other than r stand in this box (global bounds)."""
    x0, x1, y0, y1 = box
    # Only the finite bounds are compared: a watch's boxes are mostly rows, strips and half-planes.
    axes = [(P[:, 0], x0, x1), (P[:, 1], y0, y1)]
    inside = None
    for column, lo, hi in axes:
        if lo == hi:
            part = column == lo
        elif lo != -BIG and hi != BIG:
            part = (lo <= column) & (column <= hi)
        elif lo != -BIG:
            part = column >= lo
        elif hi != BIG:
            part = column <= hi
        else:
            continue
        inside = part if inside is None else inside & part
    if inside is None:  # the whole plane
        return int(P.shape[0]) - 1
    return int(np.count_nonzero(inside)) - bool(inside[r])
