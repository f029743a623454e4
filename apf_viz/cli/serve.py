"""``apf-viz serve``: the visualiser."""

from __future__ import annotations

import argparse
from pathlib import Path

from apf_viz.cli.common import add_run_options, port, shipped
from apf_viz.core.schedulers import SCHEDULERS
from apf_viz.demos import find_scenario

NAME = "serve"
HELP = "serve the visualiser (the default command)"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--host",
        default="127.0.0.1",
        help="address to bind; anyone who can reach it can follow at the class address, the presenter "
        "address drives (apf-viz docs guide, 'Who can reach the server')",
    )
    p.add_argument("--port", type=port, default=8080, help="port")
    p.add_argument(
        "--robots", type=Path, help="start file, or a shipped start's name (default: the built-in demo)"
    )
    p.add_argument(
        "--pattern", type=Path, help="pattern file, or a shipped pattern's name (default: the built-in demo)"
    )
    p.add_argument(
        "--trace", type=Path, help="open this trace (a file or a shipped trace's name), to step through it"
    )
    p.add_argument(
        "--demo",
        help="open this Demo scenario: its title, or a word naming one (heart, lockstep; apf-viz demos)",
    )
    p.add_argument(
        "--lecture",
        help="open this guided lecture (a file, or a shipped lecture's name) at its first stop, presenting",
    )
    p.add_argument(
        "--library",
        type=Path,
        help="the folder of saved patterns (Edit: Save pattern, Saved; default: the user's data directory)",
    )
    add_run_options(p, list(SCHEDULERS))


def run(args: argparse.Namespace) -> int:
    args.robots = shipped(args.robots, "robots", "--robots")
    args.pattern = shipped(args.pattern, "pattern", "--pattern")
    args.trace = shipped(args.trace, "trace", "--trace")
    if args.demo is not None:
        args.demo = find_scenario(args.demo)  # before the UI starts: a bad name is one line
    from apf_viz.ui.app import serve  # viser is imported only when the UI is wanted

    return serve(args)
