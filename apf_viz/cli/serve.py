"""``apf-viz serve``: the visualiser."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING

from apf_viz.cli.common import add_run_options, port, shipped
from apf_viz.core.schedulers import SCHEDULERS
from apf_viz.demos import find_scenario

if TYPE_CHECKING:
    from apf_viz.workbench.config import SessionConfig

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
        "--seats-per-address",
        type=seats,
        default=1,
        help="class pages from one network address that answer a question as pages of their own: one "
        "for each laptop or phone; a hall behind one router needs its size",
    )
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


def session_config(args: argparse.Namespace) -> SessionConfig:
    """The session the command line asks for: shipped names made files, a Demo word made its title (a
    bad name is one line, before the UI starts)."""
    from apf_viz.workbench.config import SessionConfig  # the workbench is loaded when a session is wanted

    return SessionConfig(
        robots=shipped(args.robots, "robots", "--robots"),
        pattern=shipped(args.pattern, "pattern", "--pattern"),
        trace=shipped(args.trace, "trace", "--trace"),
        demo=None if args.demo is None else find_scenario(args.demo),
        lecture=args.lecture,
        library=args.library,
        algorithm=args.algorithm,
        scheduler=args.scheduler,
        seed=args.seed,
        light_semantics=args.light_semantics,
    )


def run(args: argparse.Namespace) -> int:
    config = session_config(args)
    from apf_viz.ui.app import serve  # viser is imported only when the UI is wanted

    return serve(config, host=args.host, port=args.port, seats_per_address=args.seats_per_address)


def seats(text: str) -> int:
    """``--seats-per-address``: a whole number from 1 to 10,000."""
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a whole number: {text!r}") from None
    if not 1 <= n <= 10_000:
        raise argparse.ArgumentTypeError(f"{n} is not between 1 and 10000")
    return n
