"""When does a configuration equal the pattern? Up to translation and a mirror in y.

The robots agree on left and right but not on up and down, so a pattern formed upside down is formed.
"""

from __future__ import annotations

from collections.abc import Iterable

from apf_viz.core.grid import Point


def normalise(points: Iterable[Point]) -> tuple[Point, ...]:
    """The points translated so that min x = min y = 0, sorted: equal iff equal up to translation."""
    pts = list(points)
    if not pts:
        return ()
    mx = min(x for x, _ in pts)
    my = min(y for _, y in pts)
    return tuple(sorted((x - mx, y - my) for x, y in pts))


def mirror_y(points: Iterable[Point]) -> list[Point]:
    """The points mirrored in y (y → −y): the pattern as it looks formed upside down."""
    return [(x, -y) for x, y in points]


def matches_pattern(points: Iterable[Point], pattern: Iterable[Point]) -> bool:
    """True iff ``points`` is a translate of ``pattern`` or of its mirror image in y."""
    pts = normalise(points)
    pat = list(pattern)
    return pts == normalise(pat) or pts == normalise(mirror_y(pat))


def matches_only_mirrored(points: Iterable[Point], pattern: Iterable[Point]) -> bool:
    """True iff ``points`` is a translate of ``pattern``'s mirror image in y and not of ``pattern``
    itself: formed upside down (a shape symmetric top to bottom never is)."""
    pts = normalise(points)
    pat = list(pattern)
    return pts != normalise(pat) and pts == normalise(mirror_y(pat))
