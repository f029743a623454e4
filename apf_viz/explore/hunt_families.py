"""The starts a hunt draws: k robots and a pattern of k points in shapes where the paper's algorithm is
most likely to break, each with random y-axes, reproducible from (family, k, seed).

- ``square``: robots and pattern in a square box, a third of it filled.
- ``wide`` / ``tall``: the start in a box five times wider than tall (or taller than wide): long rows
  (Phase 3's line is long and the robots' walks to it short) or long columns (many robots on L_1).
- ``on-line-row``: a square start whose bottom and top rows are half full, so that whichever side the
  leader takes, robots already stand on L_H1, the row every LineMove travels along.
- ``wide-pattern`` / ``tall-pattern``: a square start, a pattern in a box three times wider (taller)
  than it: long TargetMoves past the line.
- ``sparse`` / ``dense``: a square box a tenth full (robots far apart, few blocking the view) or
  seven tenths full (many hidden robots, every column occupied).

Every start is solvable (Theorem 1; redrawn until it is), and its pattern has exactly k points.
"""

from __future__ import annotations

import math
import random
from collections.abc import Callable

from apf_viz.core.adversarial_starts import Case
from apf_viz.core.grid import Point
from apf_viz.core.symmetry import unsolvable_axis

__all__ = ["FAMILIES", "draw"]


def _cells(k: int, width: int, height: int, rng: random.Random) -> list[Point]:
    numbers = rng.sample(range(width * height), k)
    return sorted((i // height, i % height) for i in numbers)


def _box(k: int, fill: float) -> int:
    """The side of a square box that k points fill to about ``fill``."""
    return max(2, math.ceil(math.sqrt(k / fill)))


def _square(k: int, rng: random.Random) -> tuple[list[Point], list[Point]]:
    side = _box(k, 1 / 3)
    return _cells(k, side, side, rng), _cells(k, side, side, rng)


def _rectangle(k: int, rng: random.Random, wide: bool) -> tuple[list[Point], list[Point]]:
    short = max(1, math.ceil(math.sqrt(3 * k / 5)))
    long = max(k, 5 * short) if short == 1 else 5 * short
    w, h = (long, short) if wide else (short, long)
    side = _box(k, 1 / 3)
    return _cells(k, w, h, rng), _cells(k, side, side, rng)


def _on_line_row(k: int, rng: random.Random) -> tuple[list[Point], list[Point]]:
    side = max(3, _box(k, 1 / 3))
    edge = min(k // 2, side)  # robots put on the two extreme rows
    bottom = rng.sample(range(side), (edge + 1) // 2)
    top = rng.sample(range(side), edge // 2)
    cells = {(x, 0) for x in bottom} | {(x, side - 1) for x in top}
    inner = [(x, y) for x in range(side) for y in range(1, side - 1)]
    cells |= set(rng.sample(inner, k - len(cells)))
    return sorted(cells), _cells(k, side, side, rng)


def _wide_pattern(k: int, rng: random.Random, wide: bool) -> tuple[list[Point], list[Point]]:
    side = _box(k, 1 / 3)
    long = 3 * side
    w, h = (long, max(1, side // 2)) if wide else (max(1, side // 2), long)
    while w * h < k:
        w, h = (w + 1, h) if wide else (w, h + 1)
    return _cells(k, side, side, rng), _cells(k, w, h, rng)


def _density(k: int, rng: random.Random, fill: float) -> tuple[list[Point], list[Point]]:
    side = _box(k, fill)
    return _cells(k, side, side, rng), _cells(k, _box(k, 1 / 3), _box(k, 1 / 3), rng)


FAMILIES: dict[str, Callable[[int, random.Random], tuple[list[Point], list[Point]]]] = {
    "square": _square,
    "wide": lambda k, rng: _rectangle(k, rng, True),
    "tall": lambda k, rng: _rectangle(k, rng, False),
    "on-line-row": _on_line_row,
    "wide-pattern": lambda k, rng: _wide_pattern(k, rng, True),
    "tall-pattern": lambda k, rng: _wide_pattern(k, rng, False),
    "sparse": lambda k, rng: _density(k, rng, 0.1),
    "dense": lambda k, rng: _density(k, rng, 0.7),
}


def draw(family: str, k: int, seed: int) -> Case:
    """The start of ``family`` with k robots drawn from ``seed`` (redrawn until solvable), with random
    y-axes; the same (family, k, seed) always gives the same start."""
    if family not in FAMILIES:
        raise ValueError(f"unknown family {family!r}; known: {', '.join(FAMILIES)}")
    if k < 1:
        raise ValueError(f"k must be at least 1, not {k}")
    rng = random.Random(f"hunt:{family}:{k}:{seed}")
    make = FAMILIES[family]
    for _ in range(1000):
        robots, pattern = make(k, rng)
        if unsolvable_axis(robots) is None:
            return Case(family, robots, pattern, [rng.random() < 0.5 for _ in range(k)])
    raise ValueError(f"no solvable {family} start of {k} robots drawn from seed {seed}")
