"""Regenerate demo_patterns/*.json from the ASCII drawings below (run from the repository root).

'#' is a target point; rows are read top to bottom, so the drawing looks like the formed pattern.
"""

from __future__ import annotations

import json
import random
from pathlib import Path

DRAWINGS = {
    "letter-A": ["..#..", ".#.#.", "#####", "#...#", "#...#"],
    "letter-L": ["#...", "#...", "#...", "#...", "####"],
    "letter-T": ["#####", "..#..", "..#..", "..#.."],
    "letter-H": ["#..#", "#..#", "####", "#..#", "#..#"],
    "arrow": ["..#..", ".###.", "#.#.#", "..#..", "..#.."],
    "heart": [".#.#.", "#.#.#", "#...#", ".#.#.", "..#.."],
    "smiley": [".#...#.", ".......", "#.....#", ".#...#.", "..###.."],
    "spiral": ["#####", "....#", "###.#", "#...#", "#####"],
    "square-ring": ["####", "#..#", "#..#", "####"],
    "diamond": ["..#..", ".#.#.", "#...#", ".#.#.", "..#.."],
    "plus": ["..#..", "..#..", "#####", "..#..", "..#.."],
    "zigzag": ["#...#...", ".#.#.#.#", "..#...#."],
    "triangle": ["...#...", "..#.#..", ".#...#.", "#######"],
    "line-10": ["##########"],
    "cup-7": ["#...#", "#...#", ".###."],
    "block-6": ["###", "###"],
    "square-4": ["##", "##"],
    "tee-4": ["###", ".#."],
    "hook-5": ["##.", "..#", "..#", ".#."],
    "corner-3": ["#.", "##"],
    "pair-2": ["#.#"],
    "dot-1": ["#"],
}


def points(rows: list[str]) -> list[list[int]]:
    h = len(rows)
    return [[x, h - 1 - y] for y, row in enumerate(rows) for x, c in enumerate(row) if c == "#"]


def main() -> None:
    out = Path("demo_patterns")
    for name, rows in DRAWINGS.items():
        data = {"name": name, "points": points(rows)}
        (out / f"{name}.json").write_text(json.dumps(data) + "\n")
    rng = random.Random(2024)
    cells = [(x, y) for x in range(6) for y in range(6)]
    rnd = sorted(rng.sample(cells, 10))
    (out / "random-10.json").write_text(
        json.dumps({"name": "random-10", "points": [list(p) for p in rnd]}) + "\n"
    )


if __name__ == "__main__":
    main()
