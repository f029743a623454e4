"""``apf-viz random-robots``: a random solvable start."""

from __future__ import annotations

import argparse

from apf_viz.cli.common import add_box_options, emit
from apf_viz.core.files import check_writable
from apf_viz.core.formats import robots_json
from apf_viz.core.random_configs import random_robots

NAME = "random-robots"
HELP = "print a random solvable start as a robots file"
OUTPUTS = ("out",)
"""The options naming files this command writes (never one of its inputs)."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    add_box_options(p, "robots")
    p.add_argument("--allow-unsolvable", action="store_true", help="do not redraw symmetric starts")


def run(args: argparse.Namespace) -> int:
    if args.out:
        check_writable(args.out)
    points = random_robots(
        args.count, args.width, args.height, args.seed, allow_unsolvable=args.allow_unsolvable
    )
    emit(robots_json(points), args.out)
    return 0
