"""Generated starts of the adversarial families: the places where a shortcut or a reading of the paper
is most likely wrong, drawn reproducibly from a seed (the fast-forward campaign, the light lab).

- ``packed-far``: a few robots packed in a small box, one far above or below them (a long vertical walk
  that may come down its own target's column).
- ``on-column``: the same, the far robot on the column of a target as a packed robot would place it.
- ``on-row``: the far robot on the packed robots' rows, far to the left or right (a long horizontal
  walk along a row that holds robots).
- ``spread``: every robot far from the others, in a box up to ``far`` wide.
- ``symmetric-axis``: mirror-symmetric about a horizontal line through at least one robot (solvable
  by Theorem 1, and the hardest case for electing a leader), scaled.

Every start is solvable (Theorem 1) and every pattern has as many points as the start has robots.
"""

from __future__ import annotations

import random
from collections.abc import Callable
from dataclasses import dataclass

from apf_viz.core.grid import Point
from apf_viz.core.symmetry import unsolvable_axis


@dataclass(frozen=True)
class Case:
    """One generated start: its family, robots, pattern and the adversary's y-axis flips."""

    family: str
    robots: list[Point]
    pattern: list[Point]
    y_up: list[bool]


def _packed(k: int, rng: random.Random, side: int) -> list[Point]:
    cells = rng.sample(range(side * side), k)
    return [(c // side, c % side) for c in cells]


def _side(k: int) -> int:
    """The side of a small box that k points fill a good part of (3 for k ≤ 4)."""
    return max(3, k - 1)


def _pattern(k: int, rng: random.Random) -> list[Point]:
    return _packed(k, rng, _side(k))


def _distance(rng: random.Random, far: int) -> int:
    """A far distance, log-uniform from 8 to ``far``: short walks and long ones equally often."""
    return int(8 * (far / 8) ** rng.random())


def packed_far(k: int, rng: random.Random, far: int) -> tuple[list[Point], list[Point]]:
    """``packed-far``: k − 1 robots packed in a small box, one far above or below them (and a pattern of k
    points)."""
    pattern = _pattern(k, rng)
    packed = _packed(k - 1, rng, _side(k))
    x = rng.randrange(-1, _side(k) + 1)
    y = rng.choice([-1, 1]) * _distance(rng, far)
    return [*packed, (x, y)], pattern


def on_column(k: int, rng: random.Random, far: int) -> tuple[list[Point], list[Point]]:
    """``on-column``: ``packed-far`` with the far robot on (or next to) the column a target would take in the
    leader's frame: a walk that may come down its own target's column."""
    pattern = _pattern(k, rng)
    packed = _packed(k - 1, rng, _side(k))
    # A target's column in the leader's frame is a packed robot's column (the leader is likely one of
    # them, give or take the leader's own step in Phase 2) plus the target's x (the pattern is placed at
    # min x = 0).
    x = rng.choice(packed)[0] + rng.choice(pattern)[0] - min(p[0] for p in pattern) + rng.randint(-1, 1)
    y = rng.choice([-1, 1]) * _distance(rng, far)
    return [*packed, (x, y)], pattern


def on_row(k: int, rng: random.Random, far: int) -> tuple[list[Point], list[Point]]:
    """``on-row``: the far robot far to the left or right on a row of the packed robots or the pattern: a long
    horizontal walk along a row that holds robots."""
    pattern = _pattern(k, rng)
    packed = _packed(k - 1, rng, _side(k))
    rows = sorted({p[1] for p in packed} | {p[1] for p in pattern})
    x = rng.choice([-1, 1]) * _distance(rng, far)
    return [*packed, (x, rng.choice(rows))], pattern


def spread(k: int, rng: random.Random, far: int) -> tuple[list[Point], list[Point]]:
    """``spread``: k robots anywhere in a box up to ``far`` wide, every one likely far from the others (and a
    small pattern)."""
    width = _distance(rng, far)
    cells: set[Point] = set()
    while len(cells) < k:
        cells.add((rng.randrange(width), rng.randrange(width)))
    return sorted(cells), _pattern(k, rng)


def symmetric_axis(k: int, rng: random.Random, far: int) -> tuple[list[Point], list[Point]]:
    """Mirror-symmetric about y = 0 with at least one robot on the axis, scaled by 1 … ``far``∕8."""
    on_axis = rng.randint(1, k) if k % 2 else rng.randrange(2, k + 1, 2)
    on_axis = max(1, on_axis)
    half = (k - on_axis) // 2
    on_axis = k - 2 * half
    side = _side(k)
    xs = rng.sample(range(side * 2), on_axis)
    cells: set[Point] = {(x, 0) for x in xs}
    while len(cells) < k:
        p = (rng.randrange(side), rng.randrange(1, side))
        if p not in cells:
            cells |= {p, (p[0], -p[1])}
    scale = rng.randint(1, max(1, far // 8))
    return sorted((x * scale, y * scale) for x, y in cells), _pattern(k, rng)


FAMILIES: dict[str, Callable[[int, random.Random, int], tuple[list[Point], list[Point]]]] = {
    "packed-far": packed_far,
    "on-column": on_column,
    "on-row": on_row,
    "spread": spread,
    "symmetric-axis": symmetric_axis,
}


def generate(family: str, seed: int, k: int | None = None, far: int = 1000) -> Case:
    """The start of ``family`` drawn from ``seed``: k robots (2–6 if not given, 2 and 3 most often), at
    most about ``far``
    apart; redrawn until solvable."""
    rng = random.Random(f"{family}:{seed}")
    make = FAMILIES[family]
    size = k if k is not None else rng.choice((2, 2, 3, 3, 4, 5, 6))  # k = 2: the direct walk to t_0
    if family == "symmetric-axis":
        size = max(size, 3)
    for _ in range(1000):
        robots, pattern = make(size, rng, far)
        if len(set(robots)) == size and unsolvable_axis(robots) is None:
            return Case(family, robots, pattern, [rng.random() < 0.5 for _ in range(size)])
    raise ValueError(f"no solvable {family} start of {size} robots drawn from seed {seed}")


def symmetric_start(k: int, seed: int) -> tuple[list[Point], list[Point], list[bool]]:
    """A random ``symmetric-axis`` start of exactly k robots (scaled ×1 to ×3), a random pattern of k
    points and random flips, from ``seed`` (the light lab's random symmetric starts)."""
    rng = random.Random(f"symmetric:{k}:{seed}")
    robots, pattern = symmetric_axis(k, rng, 24)
    return robots, pattern, [rng.random() < 0.5 for _ in range(k)]
