"""The infinite grid Z²: points, the four unit moves, and opaque visibility.

Robot ``r`` sees robot ``q`` iff no robot lies strictly inside the segment r–q (paper §2, *Visibility*).
On the lattice the only grid points inside that segment are ``r + t·(dx, dy)/g`` for ``t = 1..g−1``,
``g = gcd(|dx|, |dy|)``. So ``q`` is visible iff it is the *nearest* robot along its primitive direction
``(dx, dy)/g``: one Look costs one pass over the k robots (:func:`visible_from`), not a walk over lattice
points (:func:`visible_from_naive`, kept as the test oracle).
"""

from __future__ import annotations

from enum import Enum
from math import gcd

import numpy as np

Point = tuple[int, int]


class Direction(Enum):
    """A unit move along a grid edge, in whichever frame the caller works in."""

    LEFT = "left"
    RIGHT = "right"
    UP = "up"
    DOWN = "down"

    @property
    def delta(self) -> Point:
        return _DELTAS[self]

    @classmethod
    def from_delta(cls, dx: int, dy: int) -> Direction:
        for d, v in _DELTAS.items():
            if v == (dx, dy):
                return d
        raise ValueError(f"({dx}, {dy}) is not a unit grid move")


_DELTAS: dict[Direction, Point] = {
    Direction.LEFT: (-1, 0),
    Direction.RIGHT: (1, 0),
    Direction.UP: (0, 1),
    Direction.DOWN: (0, -1),
}

# Primitive directions are packed into one int64 key; offsets beyond ±2**30 are not a grid we simulate.
_KEY_SHIFT = np.int64(1 << 31)


def visible_from(positions: np.ndarray, i: int) -> np.ndarray:
    """Indices of the robots that robot ``i`` sees, in increasing order.

    Args:
        positions: shape (k, 2), distinct integer points.
        i: the observer's index.

    Vectorised "nearest robot per primitive direction": O(k log k) in numpy, no lattice walk.
    """
    offsets = positions - positions[i]
    others = np.flatnonzero(np.any(offsets != 0, axis=1))
    if others.size == 0:
        return others
    d = offsets[others]
    g = np.gcd(d[:, 0], d[:, 1])
    key = (d[:, 0] // g) * _KEY_SHIFT + (d[:, 1] // g)
    order = np.lexsort((g, key))  # by direction, nearest first
    sorted_key = key[order]
    first = np.ones(sorted_key.size, dtype=bool)
    first[1:] = sorted_key[1:] != sorted_key[:-1]
    return np.sort(others[order[first]])


def visible_from_naive(points: list[Point], i: int) -> list[int]:
    """Oracle: walk every interior lattice point of every segment (O(k · span)); tests only."""
    occupied = set(points)
    x0, y0 = points[i]
    seen = []
    for j, (x1, y1) in enumerate(points):
        if j == i:
            continue
        dx, dy = x1 - x0, y1 - y0
        g = gcd(abs(dx), abs(dy))
        if all((x0 + t * dx // g, y0 + t * dy // g) not in occupied for t in range(1, g)):
            seen.append(j)
    return seen
