"""``apf-viz random-pattern``: a random pattern."""

from __future__ import annotations

import argparse

from apf_viz.cli.common import add_box_options, emit
from apf_viz.core.files import check_writable
from apf_viz.core.formats import pattern_json
from apf_viz.core.random_configs import random_pattern

NAME = "random-pattern"
HELP = "print a random pattern as a pattern file"
OUTPUTS = ("out",)
"""The options naming files this command writes (never one of its inputs)."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    add_box_options(p, "pattern points")
    p.add_argument("--name", help="the pattern's name in the file")


def run(args: argparse.Namespace) -> int:
    if args.out:
        check_writable(args.out)
    emit(pattern_json(random_pattern(args.count, args.width, args.height, args.seed), args.name), args.out)
    return 0
