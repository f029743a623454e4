"""The infinite grid Z²: points, the four unit moves, and opaque visibility.

Robot ``r`` sees robot ``q`` iff no robot lies strictly inside the segment r–q (paper §2, *Visibility*).
On the lattice the only grid points inside that segment are ``r + t·(dx, dy)/g`` for ``t = 1..g−1``,
``g = gcd(|dx|, |dy|)``. So ``q`` is visible iff it is the *nearest* robot along its primitive direction
``(dx, dy)/g``: one Look costs one pass over the k robots (:func:`visible_from`), not a walk over lattice
points (tests/oracle.py walks them: the tests' oracle).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Iterable, Sequence
from enum import Enum

import numpy as np

Point = tuple[int, int]

COORD_LIMIT = 10**12
"""The largest |x| or |y| a start, a pattern or a click may have (docs/ARCHITECTURE.md, *Coordinates*).

The grid is infinite, but the engine keeps positions in int64. Inside this range every position,
offset, gcd and sort key is exact with room to spare: offsets stay below 2^41 plus the moves made, and a
run would need about 4·10^18 moves to reach int64's limit."""


def as_point(p: Sequence[int]) -> Point:
    """A point from any pair (a JSON list, a numpy row, a tuple); not a pair is refused."""
    x, y = p
    return (x, y)


def short_int(v: int) -> str:
    """An integer for a one-line message: in full below 10^15, else its order of magnitude (never the
    digits of a huge number, which Python even refuses to print beyond 4,300 of them)."""
    if abs(v) < 10**15:
        return str(v)
    return f"{'-' if v < 0 else ''}~10^{math.floor(math.log10(abs(v)))}"


def coordinate_problem(points: Iterable[Sequence[int]], what: str) -> str | None:
    """A one-line description of the first point outside ±COORD_LIMIT (``what`` names the points, e.g.
    "robot"), or None when all are inside."""
    for i, (x, y) in enumerate(points):
        if abs(x) > COORD_LIMIT or abs(y) > COORD_LIMIT:
            return (
                f"{what} {i} at ({short_int(x)}, {short_int(y)}) is outside the supported range: "
                f"|x| and |y| must be at most {COORD_LIMIT:,}"
            )
    return None


class Direction(Enum):
    """A unit move along a grid edge, in whichever frame the caller works in."""

    LEFT = "left"
    RIGHT = "right"
    UP = "up"
    DOWN = "down"

    @property
    def delta(self) -> Point:
        """The move as a grid offset (dx, dy)."""
        return _DELTAS[self]

    @classmethod
    def from_delta(cls, dx: int, dy: int) -> Direction:
        """The direction of a unit offset (a ValueError for any other)."""
        d = _FROM_DELTA.get((dx, dy))
        if d is None:
            raise ValueError(f"({dx}, {dy}) is not a unit grid move")
        return d


_DELTAS: dict[Direction, Point] = {
    Direction.LEFT: (-1, 0),
    Direction.RIGHT: (1, 0),
    Direction.UP: (0, 1),
    Direction.DOWN: (0, -1),
}
_FROM_DELTA: dict[Point, Direction] = {v: d for d, v in _DELTAS.items()}

# Below this offset span one packed int64 sort key per robot is exact; above it, a three-key sort.
PACKED_SPAN_LIMIT = 1 << 20
# Offsets up to this size in both coordinates have their distance and direction in tables (two arrays of
# (2·TABLE_SPAN + 1)² int64, 1 MiB each).
TABLE_SPAN = 180
TABLE_WIDTH = 2 * TABLE_SPAN + 1
TABLE_CENTRE = TABLE_SPAN * TABLE_WIDTH + TABLE_SPAN  # where offset (0, 0) sits in the tables


@functools.cache
def _direction_tables() -> tuple[np.ndarray, np.ndarray]:
    """For every offset (dx, dy) with |dx|, |dy| ≤ TABLE_SPAN, flattened row by row from (−T, −T): its
    lattice distance g = gcd(|dx|, |dy|) (1 for (0, 0)) and its primitive direction packed as one key
    (dx/g)·(2T + 1) + dy/g, which orders directions by (dx/g, dy/g)."""
    axis = np.arange(-TABLE_SPAN, TABLE_SPAN + 1, dtype=np.int64)
    g = np.gcd.outer(axis, axis)
    g[TABLE_SPAN, TABLE_SPAN] = 1
    key = (axis[:, None] // g) * TABLE_WIDTH + axis[None, :] // g
    return g.ravel(), key.ravel()


def visible_from(positions: np.ndarray, i: int) -> np.ndarray:
    """Indices of the robots that robot ``i`` sees, in increasing order.

    Args:
        positions: shape (k, 2), distinct integer points.
        i: the observer's index.
    """
    return np.sort(nearest_per_direction(positions - positions[i], i))


_FAR = np.iinfo(np.int64).max
_LEAST = np.iinfo(np.int64).min


def table_scratch() -> np.ndarray:
    """A caller's own work array for :func:`visible_in_crowd` (1 MiB; every entry ``_FAR`` between calls)."""
    return np.full(TABLE_WIDTH**2, _FAR, dtype=np.int64)


def table_index(offsets: np.ndarray) -> np.ndarray:
    """Where each offset (|dx|, |dy| ≤ TABLE_SPAN) sits in the direction tables."""
    index: np.ndarray = offsets[:, 0] * TABLE_WIDTH + offsets[:, 1] + TABLE_CENTRE
    return index


def visible_in_crowd(at: np.ndarray, i: int, scratch: np.ndarray) -> np.ndarray:
    """The robots visible from robot i, in increasing index order, given where each robot's offset from
    it sits in the direction tables (:func:`table_index`; every offset at most TABLE_SPAN in both
    coordinates, the caller checks): "nearest robot per primitive direction" without a sort.
    ``np.minimum.at`` leaves, per direction, the least (distance, index) in ``scratch``, and a robot is
    visible iff it is that least one. ``scratch`` (from :func:`table_scratch`) is restored before
    returning."""
    k = at.shape[0]
    distance, direction = _direction_tables()
    slot = direction[at] + TABLE_CENTRE  # the direction key, made non-negative
    rank = distance[at] * k + np.arange(k)  # by distance, then index: distinct
    rank[i] = _FAR  # the observer is nobody's nearest
    np.minimum.at(scratch, slot, rank)
    nearest = rank == scratch[slot]
    scratch[slot] = _FAR
    nearest[i] = False
    seen: np.ndarray = nearest.nonzero()[0]
    return seen


def nearest_per_direction(offsets: np.ndarray, i: int, span: int | None = None) -> np.ndarray:
    """The visible robots, given every robot's offset from observer ``i`` (shape (k, 2); row i is 0).

    "Nearest robot per primitive direction", vectorised: one gcd, one sort of k packed keys
    (direction, distance g), and the first of each direction wins; no lattice point is visited.
    The result is ordered by direction, a function of the offsets alone (no robot identity).
    ``span``, if given, is a bound the caller knows: every |offset| coordinate < span.
    """
    k = offsets.shape[0]
    if k == 1:
        return np.empty(0, dtype=np.intp)
    dx, dy = offsets[:, 0], offsets[:, 1]
    if span is None:
        span = int(np.abs(offsets).max()) + 1
    if span <= TABLE_SPAN:
        # A crowd: every offset's distance and direction key looked up in tables made once, instead of a
        # gcd and two divisions per robot (distance ≤ TABLE_SPAN, so the packed key cannot collide).
        distance, direction = _direction_tables()
        at = table_index(offsets)
        key = direction[at]
        packed = key * (TABLE_SPAN + 1) + distance[at]
        packed[i] = _LEAST
        order = packed.argsort()  # the keys are distinct: no need for a stable sort
        sorted_key = key[order]
        first = np.empty(k, dtype=bool)
        np.not_equal(sorted_key[2:], sorted_key[1:-1], out=first[2:])
        first[0] = False  # the observer
        first[1] = True
        seen: np.ndarray = order[first]
        return seen
    g = np.gcd(dx, dy)
    g[i] = 1  # the observer itself: offset (0, 0), sorted first and dropped below
    ddx, ddy = dx // g, dy // g  # the primitive direction of each robot
    if span < PACKED_SPAN_LIMIT:
        # One packed key (direction, then distance g) sorts fastest; below this span it cannot overflow:
        # |key| < (2·span + 1)², |packed| < (2·span + 1)² · span + span < 2^63.
        key = ddx * (2 * span + 1) + ddy  # unique per primitive direction
        packed = key * span + g  # by direction, nearest first
        packed[i] = _LEAST
        order = packed.argsort()  # distinct keys (a point is its direction and distance): any sort
        sorted_key = key[order]
        first = np.empty(k, dtype=bool)
        np.not_equal(sorted_key[2:], sorted_key[1:-1], out=first[2:])
    else:
        # Far apart: sort by the direction's two components and the distance as three keys, so no sum or
        # product of coordinates is formed (exact for every offset int64 holds).
        ddx[i] = _LEAST  # the observer sorts first
        order = np.lexsort((g, ddy, ddx))
        sx, sy = ddx[order], ddy[order]
        first = np.empty(k, dtype=bool)
        first[2:] = (sx[2:] != sx[1:-1]) | (sy[2:] != sy[1:-1])
    first[0] = False  # the observer
    first[1] = True
    in_sight: np.ndarray = order[first]
    return in_sight


def hiders(points: Sequence[Point], i: int) -> dict[int, int]:
    """Each robot that robot ``i`` cannot see, with the robot that hides it: the nearest robot on the
    same line of sight (primitive direction), which ``i`` sees. Exact integer arithmetic, O(k)."""
    x0, y0 = points[i]
    nearest: dict[tuple[int, int], tuple[int, int]] = {}  # direction → (distance, robot)
    by_robot: dict[int, tuple[tuple[int, int], int]] = {}
    for j, (x, y) in enumerate(points):
        if j == i:
            continue
        dx, dy = x - x0, y - y0
        g = math.gcd(dx, dy)
        direction = (dx // g, dy // g)
        by_robot[j] = (direction, g)
        if direction not in nearest or g < nearest[direction][0]:
            nearest[direction] = (g, j)
    return {j: nearest[d][1] for j, (d, g) in by_robot.items() if nearest[d][1] != j}
