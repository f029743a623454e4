"""Regenerate demo_patterns/*.json from the ASCII drawings below (run from the repository root).

'#' is a target point; rows are read top to bottom, so the drawing looks like the formed pattern.
"""

from __future__ import annotations

import argparse
import json
import random
from pathlib import Path

from apf_viz.core.files import write_atomic

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
    argparse.ArgumentParser(description=__doc__.splitlines()[0]).parse_args()  # --help, and no other
    out = Path("demo_patterns")
    for name, rows in DRAWINGS.items():
        data = {"name": name, "points": points(rows)}
        write_atomic(out / f"{name}.json", json.dumps(data) + "\n")
    rng = random.Random(2024)
    cells = [(x, y) for x in range(6) for y in range(6)]
    rnd = sorted(rng.sample(cells, 10))
    data = {"name": "random-10", "points": [list(p) for p in rnd]}
    write_atomic(out / "random-10.json", json.dumps(data) + "\n")


if __name__ == "__main__":
    main()
