"""``apf-viz replay``: re-run a trace and check every event."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from apf_viz.algorithms import algorithm_from_command_line, get_algorithm
from apf_viz.cli.common import EXIT_FORMED, EXIT_NOT_FORMED, print_summary, shipped
from apf_viz.core.formats import InputError, load_trace
from apf_viz.core.run import RunSummary, engine_for_trace, replay

NAME = "replay"
HELP = "re-run a trace file exactly and check every event"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--trace", required=True, type=Path, help="the trace file (JSON Lines)")
    p.add_argument(
        "--algorithm",
        help="replay with this algorithm instead of the one the trace names (the only way to replay a "
        "trace of your own module:Name algorithm: a file never loads code)",
    )
    p.add_argument("--json", action="store_true", help="print the outcome as one JSON object")


def run(args: argparse.Namespace) -> int:
    args.trace = shipped(args.trace, "trace", "--trace")
    header, events = load_trace(args.trace)
    if args.algorithm:
        algorithm, _ = algorithm_from_command_line(args.algorithm)
    else:
        try:
            algorithm = get_algorithm(header.algorithm)  # a file names built-in algorithms only
        except ValueError as e:
            raise InputError(
                f"{args.trace}: {e}; to replay it with an algorithm of your own, pass --algorithm"
            ) from None
    engine = engine_for_trace(header, algorithm)
    replay(engine, events, str(args.trace))  # a mismatch: one line naming the event, exit 2
    summary = RunSummary.of(engine)
    if not args.json:
        print(f"replayed: all {len(events):,} events of {args.trace} match the engine's, one by one")
    print_summary(summary, args.json)
    if summary.outcome == "running" and not args.json:
        print(f"apf-viz: the trace ends after {summary.events} events, before the run does", file=sys.stderr)
    return EXIT_FORMED if summary.outcome == "formed" else EXIT_NOT_FORMED
