"""``apf-viz export``: a lecture or a run as one HTML page that plays anywhere, with no server."""

from __future__ import annotations

import argparse
from pathlib import Path

from apf_viz.cli.common import add_run_options
from apf_viz.cli.sessions import start_session, trace_session
from apf_viz.core.files import check_writable, write_atomic
from apf_viz.core.formats import InputError
from apf_viz.core.schedulers import AUTOMATIC

NAME = "export"
HELP = "a lecture or a run as one HTML page that plays from disk, with no server and no network"
OUTPUTS = ("out",)
"""The options naming files this command writes (never one of its inputs)."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--lecture", help="a shipped lecture's name, or a lecture file: every stop, its words")
    p.add_argument("--trace", type=Path, help="a trace (a counterexample, a sweep's failure): its run")
    p.add_argument("--robots", type=Path, help="with --pattern: a run from this start to its end")
    p.add_argument("--pattern", type=Path, help="the pattern (a file, or a shipped name)")
    p.add_argument("--out", type=Path, required=True, help="the page to write (atomically)")
    add_run_options(p, AUTOMATIC)


def run(args: argparse.Namespace) -> int:
    from apf_viz.ui.page_export import export_lecture, export_run
    from apf_viz.workbench.session.demo import demo_session

    check_writable(args.out)
    if args.lecture is not None:
        from apf_viz.lecture import find_lecture

        lecture = find_lecture(args.lecture)
        exported = export_lecture(demo_session(), lecture)
        what = f"{lecture.title}: {len(lecture.stops)} stops"
    elif args.trace is not None:
        session, name = trace_session(args.trace)
        exported = export_run(session, name)
        what = name
    elif args.robots is not None and args.pattern is not None:
        session, robots, pattern = start_session(args)
        exported = export_run(session, f"{robots} → {pattern}, {args.scheduler}, seed {args.seed}")
        what = f"{robots} to its end"
    else:
        raise InputError("export: give --lecture NAME, --trace T, or --robots R with --pattern P")
    write_atomic(args.out, exported.html)
    size = len(exported.html.encode()) / 1e6
    counts = f"{exported.frames} frames, {exported.events} events, {size:.1f} MB"
    print(f"apf-viz export: {args.out} ({what}; {counts})")
    return 0
