"""The visibility oracle the tests hold the engine to: a walk over every lattice point inside each
segment (O(k · span)), sharing no code with apf_viz (core/grid.py finds the same robots in O(k) by the
nearest robot per primitive direction)."""

from __future__ import annotations

from math import gcd


def visible_by_lattice_walk(points: list[tuple[int, int]], i: int) -> list[int]:
    """The robots robot ``i`` sees, in index order: those with no robot strictly inside the segment to
    them (paper §2, *Visibility*). The interior lattice points of a segment with offset (dx, dy) are
    ``i + t·(dx, dy)/g`` for t = 1..g−1, g = gcd(|dx|, |dy|)."""
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
