"""Random starts and patterns in a box, reproducible from a seed (``apf-viz random-robots`` and
``random-pattern``).

The box is [0, width) × [0, height); its cells are numbered x-major (cell i is (i // height, i % height))
and ``count`` distinct numbers are drawn with :meth:`random.Random.sample` on a ``range`` (or, past
2^63 cells, where a ``range`` has no length, by repeated draws), so a box of 10^24 cells costs no more
than one of 100: nothing but the drawn cells is ever built.
"""

from __future__ import annotations

import random
import sys

from apf_viz.core.grid import COORD_LIMIT, Point
from apf_viz.core.symmetry import unsolvable_axis

MAX_RANDOM_POINTS = 100_000  # robots or pattern points per file: a bigger run is not one apf-viz can show
_SOLVABLE_TRIES = 1000


def box_problem(count: int, width: int, height: int) -> str | None:
    """Why ``count`` distinct cells cannot be drawn from a width × height box, or None."""
    if count < 1 or width < 1 or height < 1:
        return "--count, --width and --height must be at least 1"
    if count > MAX_RANDOM_POINTS:
        return f"--count {count:,} is more than {MAX_RANDOM_POINTS:,} points"
    if width > COORD_LIMIT + 1 or height > COORD_LIMIT + 1:
        return f"--width and --height must be at most {COORD_LIMIT + 1:,} (coordinates 0..{COORD_LIMIT:,})"
    if count > width * height:
        return f"--count {count} points do not fit in a {width}×{height} box"
    return None


def sample_cells(count: int, width: int, height: int, rng: random.Random) -> list[Point]:
    """``count`` distinct cells of the box, sorted; the box itself is never materialised."""
    problem = box_problem(count, width, height)
    if problem:
        raise ValueError(problem)
    cells = width * height
    if cells <= sys.maxsize:
        numbers = rng.sample(range(cells), count)
    else:  # len(range) must fit a C ssize_t; in a box this big, draws almost never repeat
        drawn: dict[int, None] = {}
        while len(drawn) < count:
            drawn.setdefault(rng.randrange(cells))
        numbers = list(drawn)
    return sorted((i // height, i % height) for i in numbers)


def random_robots(
    count: int, width: int, height: int, seed: int, *, allow_unsolvable: bool = False
) -> list[Point]:
    """A random start; unless ``allow_unsolvable``, redrawn until it is solvable (Theorem 1)."""
    rng = random.Random(seed)
    for _ in range(_SOLVABLE_TRIES):
        points = sample_cells(count, width, height, rng)
        if allow_unsolvable or unsolvable_axis(points) is None:
            return points
    raise ValueError("could not draw a solvable start in this box; widen it or pass --allow-unsolvable")


def random_pattern(count: int, width: int, height: int, seed: int) -> list[Point]:
    """A random pattern (any set of distinct cells is a pattern)."""
    return sample_cells(count, width, height, random.Random(seed))
