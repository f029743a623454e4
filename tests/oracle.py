"""The visibility oracles the tests hold the engine to, sharing no code with apf_viz (core/grid.py finds
the same robots in O(k) by the nearest robot per primitive direction): a walk over every lattice point
inside each segment (O(k · span)), and betweenness by exact cross and dot products (O(k²), any span)."""

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


def visible_by_betweenness(points: list[tuple[int, int]], i: int) -> list[int]:
    """Robot j is visible from i iff no robot lies strictly inside the segment i–j (exact integers)."""
    x0, y0 = points[i]
    out = []
    for j, (x1, y1) in enumerate(points):
        if j == i:
            continue
        dx, dy = x1 - x0, y1 - y0
        blocked = False
        for m, (x, y) in enumerate(points):
            if m in (i, j):
                continue
            px, py = x - x0, y - y0
            if px * dy - py * dx == 0 and 0 < px * dx + py * dy < dx * dx + dy * dy:
                blocked = True
                break
        if not blocked:
            out.append(j)
    return out
