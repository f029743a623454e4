"""``apf-viz schedule``: the schedule of a trace."""

from __future__ import annotations

import argparse
from pathlib import Path

from apf_viz.cli.common import emit, shipped
from apf_viz.core.files import check_writable, write_atomic
from apf_viz.core.formats import load_trace, pattern_json, robots_json
from apf_viz.core.schedule import schedule_of_trace, schedule_text

NAME = "schedule"
HELP = "write the schedule (who acted and the flips, not what they saw) of a trace"
OUTPUTS = ("out", "robots_out", "pattern_out")
"""The options naming files this command writes (never one of its inputs)."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--from-trace", required=True, type=Path, help="the trace (JSON Lines), or a shipped trace's name"
    )
    p.add_argument("--out", type=Path, help="write to this file (atomically) instead of standard output")
    p.add_argument(
        "--robots-out", type=Path, help="also write the trace's start (with its flips) as a robots file"
    )
    p.add_argument("--pattern-out", type=Path, help="also write the trace's pattern as a pattern file")


def run(args: argparse.Namespace) -> int:
    for out in (args.out, args.robots_out, args.pattern_out):
        if out:
            check_writable(out)  # before reading a trace of a million lines, not after
    args.from_trace = shipped(args.from_trace, "trace", "--from-trace")  # a shipped trace by its name too
    header, events = load_trace(args.from_trace)
    lc_atomic = header.light_semantics == "lc-atomic"
    y_up = header.y_up if header.y_up is not None else [True] * len(header.robots)  # as the replay does
    text = schedule_text(
        len(header.robots), schedule_of_trace(events, lc_atomic), y_up, header.light_semantics
    )
    if args.robots_out:
        write_atomic(args.robots_out, robots_json(header.robots, y_up))
    if args.pattern_out:
        write_atomic(args.pattern_out, pattern_json(header.pattern, f"pattern of {args.from_trace.name}"))
    emit(text, args.out)
    return 0
