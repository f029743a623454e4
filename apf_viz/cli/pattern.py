"""``apf-viz pattern``: a pattern (or robots) file from text, ASCII art or a shape."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from apf_viz.cli.common import emit, fail
from apf_viz.core import shapes
from apf_viz.core.files import check_writable, read_text
from apf_viz.core.formats import MAX_INPUT_BYTES, InputError, pattern_json, robots_json
from apf_viz.core.symmetry import describe_axis, unsolvable_axis

NAME = "pattern"
HELP = "make a pattern (or robots) file from text, ASCII art or a shape"
OUTPUTS = ("out",)
"""The options naming files this command writes (never one of its inputs)."""


SHAPES = {
    "ring": lambda n: shapes.ring((0, 0), n),
    "disc": lambda n: shapes.disc((0, 0), n),
    "box": lambda n: shapes.box((0, 0), (n - 1, n - 1)),
    "outline": lambda n: shapes.outline((0, 0), (n - 1, n - 1)),
    "row": lambda n: shapes.row((0, 0), n),
    "column": lambda n: shapes.column((0, 0), n),
    "staircase": lambda n: shapes.staircase((0, 0), n),
}
# The least --size of each shape: a ring or a disc of radius 0 is one cell; a box of side 0 is nothing
# (and a side below 0 would be read as a box the other way round).
_LEAST_SIZE = {"ring": 0, "disc": 0}


def add_arguments(p: argparse.ArgumentParser) -> None:
    source = p.add_mutually_exclusive_group(required=True)
    source.add_argument("--text", help="letters A-Z, digits and spaces in a 3x5 font")
    source.add_argument("--ascii", type=Path, help="a text file: '#' is a cell, the first line the top row")
    source.add_argument(
        "--shape", choices=list(SHAPES), help="a shape of --size (a ring's radius, a row's length)"
    )
    p.add_argument("--size", type=int, default=4, help="the shape's radius, length, steps or side")
    p.add_argument(
        "--mirror",
        choices=["x", "y"],
        action="append",
        default=[],
        help="mirror left-right (x) or up-down (y)",
    )
    p.add_argument("--rotate", type=int, choices=[0, 1, 2, 3], default=0, help="quarter turns anticlockwise")
    p.add_argument(
        "--scale", type=int, choices=[1, 2, 3, 4], default=1, help="each cell a scale x scale block"
    )
    p.add_argument(
        "--count",
        type=int,
        help="fit to this many cells: the last drawn removed, or cells added along the outline",
    )
    p.add_argument(
        "--as", dest="kind", choices=["pattern", "robots"], default="pattern", help="the file to write"
    )
    p.add_argument("--name", help="the pattern's name in the file")
    p.add_argument("--out", type=Path, help="write to this file (atomically) instead of standard output")


def run(args: argparse.Namespace) -> int:
    """A drawing made from a specification, then mirrored, turned, scaled and fitted in that order."""
    if args.out:
        check_writable(args.out)
    if args.text is not None:
        cells = shapes.text(args.text, (0, 0))
        if not cells:
            fail(f"--text {args.text!r}: no cells to draw (only spaces)")
    elif args.ascii is not None:
        lines = read_text(args.ascii, MAX_INPUT_BYTES).splitlines()
        try:
            cells = shapes.ascii_art(lines)
        except shapes.ShapeError as e:
            raise InputError(f"{args.ascii}: {e}") from None
        if not cells:
            raise InputError(f"{args.ascii}: no '#' cell in it")
    else:
        least = _LEAST_SIZE.get(args.shape, 1)
        if not least <= args.size <= shapes.MAX_SIZE:
            fail(f"--shape {args.shape} --size {args.size}: choose a whole number from {least} to "
                  f"{shapes.MAX_SIZE:,}")  # fmt: skip
        cells = SHAPES[args.shape](args.size)
    for axis in args.mirror:
        cells = shapes.mirrored(cells, axis)
    for _ in range(args.rotate):
        cells = shapes.rotated(cells)
    cells = shapes.scaled(cells, args.scale)
    if args.count is not None:
        cells, said = shapes.fitted(cells, args.count)
        print(f"apf-viz pattern: fit to {args.count}: {said}", file=sys.stderr)
    if args.kind == "robots":
        axis = unsolvable_axis(cells)
        if axis is not None:
            note = f"these robots are unsolvable (Theorem 1: mirror axis {describe_axis(axis)})"
            print(f"apf-viz pattern: note: {note}", file=sys.stderr)
        emit(robots_json(cells), args.out)
    else:
        emit(pattern_json(cells, args.name or _name_of(args)), args.out)
    return 0


def _name_of(args: argparse.Namespace) -> str:
    """The pattern's name when --name gives none: what it was made from."""
    if args.text is not None:
        return args.text
    if args.ascii is not None:
        return args.ascii.stem
    return f"{args.shape} of size {args.size}"
