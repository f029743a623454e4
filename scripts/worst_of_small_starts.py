"""The exact worst moves/(k·D) of every 3-robot start in a 4 × 4 box (translated to touch both axes) to
a row, a column, an L or a diagonal of three, over every schedule and every flip (docs/ADVERSARY.md,
"The largest moves/(k·D) measured"). Prints the six largest and how many pairs were solvable.
Run: python scripts/worst_of_small_starts.py   (about a minute)"""

from __future__ import annotations

import itertools

import apf_viz
from apf_viz.core.formats import InputError

PATTERNS = {
    "row": [(0, 0), (1, 0), (2, 0)],
    "column": [(0, 0), (0, 1), (0, 2)],
    "L": [(0, 0), (1, 0), (0, 1)],
    "diagonal": [(0, 0), (1, 1), (2, 2)],
}


def main() -> None:
    cells = [(x, y) for x in range(4) for y in range(4)]
    found = []
    for robots in itertools.combinations(cells, 3):
        if min(x for x, _ in robots) or min(y for _, y in robots):
            continue  # a translate of another start
        for name, pattern in PATTERNS.items():
            try:
                w = apf_viz.check(list(robots), pattern, worst="moves", flips="all", progress=False)
            except InputError:  # unsolvable (Theorem 1)
                continue
            if w.value is not None:
                found.append((w.value / (w.k * w.D), w.value, w.k * w.D, robots, name))
    found.sort(reverse=True)
    for per_kD, moves, kD, robots, name in found[:6]:
        print(f"{per_kD:.3f} moves/(k·D): {moves} moves, k·D = {kD}, robots {list(robots)} to a {name}")
    print(f"{len(found)} solvable pairs")


if __name__ == "__main__":
    main()
