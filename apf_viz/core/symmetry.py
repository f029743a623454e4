"""Theorem 1 (paper §3): APF is solvable iff the start is not mirror-symmetric about a horizontal line K
that passes through no robot.

Only a horizontal axis matters because the robots agree on left and right, and a finite set can be
symmetric about at most one horizontal line: y = (y_min + y_max) / 2.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from fractions import Fraction

from apf_viz.core.grid import Point


def unsolvable_axis(robots: Iterable[Point]) -> Fraction | None:
    """The axis y = c of the unsolvable symmetry of Theorem 1, or None if the start is solvable."""
    pts = set(robots)
    if not pts:
        return None
    ys = [y for _, y in pts]
    c2 = min(ys) + max(ys)  # twice the only candidate axis
    if any(2 * y == c2 for y in ys):
        return None  # the axis passes through a robot
    if all((x, c2 - y) in pts for x, y in pts):
        return Fraction(c2, 2)
    return None


def mirror_axis(robots: Iterable[Point]) -> Fraction | None:
    """The horizontal line y = c the robots are mirror-symmetric about, through robots or not (None:
    none). Through no robot it is Theorem 1's unsolvable axis; through robots, the paper's K."""
    pts = set(robots)
    if not pts:
        return None
    ys = [y for _, y in pts]
    c2 = min(ys) + max(ys)
    return Fraction(c2, 2) if all((x, c2 - y) in pts for x, y in pts) else None


def describe_axis(c: Fraction) -> str:
    """``y = c`` written exactly (the axis lies halfway between two rows: c is a whole number plus ½)."""
    if c.denominator == 1:
        return f"y = {c.numerator}"
    whole, _ = divmod(abs(c.numerator), 2)
    return f"y = {'-' if c < 0 else ''}{whole}.5"


def unsolvable_start(robots: Sequence[Point], pattern: Sequence[Point]) -> tuple[Fraction, str] | None:
    """Theorem 1 refuses this start: its axis, and why in words (the command line and the library each
    add how to run it anyway). None when it is solvable, or already the pattern."""
    from apf_viz.core.pattern_match import matches_pattern

    axis = unsolvable_axis(robots)
    if axis is None or matches_pattern(robots, pattern):
        return None
    why = (
        f"unsolvable start: mirror-symmetric about {describe_axis(axis)}, a horizontal line through no "
        "robot (Theorem 1)"
    )
    return axis, why
