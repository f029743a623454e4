"""``apf-viz export``: a lecture or a run as one HTML page that plays anywhere, with no server."""

from __future__ import annotations

import argparse
from pathlib import Path

from apf_viz.algorithms import algorithm_from_command_line
from apf_viz.cli.common import add_run_options, shipped
from apf_viz.core.formats import (
    MAX_TRACE_BYTES,
    InputError,
    check_writable,
    load_pattern,
    load_robots,
    load_trace,
    write_atomic,
)
from apf_viz.core.grid import as_point
from apf_viz.core.schedulers import AUTOMATIC

NAME = "export"
HELP = "a lecture or a run as one HTML page that plays from disk, with no server and no network"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--lecture", help="a shipped lecture's name, or a lecture file: every stop, its words")
    p.add_argument("--trace", type=Path, help="a trace (a counterexample, a sweep's failure): its run")
    p.add_argument("--robots", type=Path, help="with --pattern: a run from this start to its end")
    p.add_argument("--pattern", type=Path, help="the pattern (a file, or a shipped name)")
    p.add_argument("--out", type=Path, required=True, help="the page to write (atomically)")
    add_run_options(p, AUTOMATIC)


def run(args: argparse.Namespace) -> int:
    from apf_viz.ui.app import demo_session
    from apf_viz.ui.page_export import export_lecture, export_run

    check_writable(args.out)
    if args.lecture is not None:
        from apf_viz.lecture import find_lecture

        lecture = find_lecture(args.lecture)
        exported = export_lecture(demo_session(), lecture)
        what = f"{lecture.title}: {len(lecture.stops)} stops"
    elif args.trace is not None:
        path = shipped(args.trace, "trace", "--trace")
        assert path is not None
        load_trace(path)  # a missing or malformed file: one line, before anything
        session = demo_session()
        session.load_trace(path.name, path.read_bytes(), MAX_TRACE_BYTES)
        exported = export_run(session, f"{path.name}")
        what = f"{path.name}"
    elif args.robots is not None and args.pattern is not None:
        exported = export_run(*_run(args))
        what = f"{args.robots.name} to its end"
    else:
        raise InputError("export: give --lecture NAME, --trace T, or --robots R with --pattern P")
    write_atomic(args.out, exported.html)
    size = len(exported.html.encode()) / 1e6
    counts = f"{exported.frames} frames, {exported.events} events, {size:.1f} MB"
    print(f"apf-viz export: {args.out} ({what}; {counts})")
    return 0


def _run(args: argparse.Namespace):
    from apf_viz.ui.session import Session

    robots_path = shipped(args.robots, "robots", "--robots")
    pattern_path = shipped(args.pattern, "pattern", "--pattern")
    assert robots_path is not None and pattern_path is not None
    robots, pattern = load_robots(robots_path), load_pattern(pattern_path)
    algorithm, plugins = algorithm_from_command_line(args.algorithm)
    session = Session(
        [as_point(p) for p in robots.robots],
        [as_point(p) for p in pattern.points],
        y_up=robots.flips(args.seed),
        algorithm=algorithm.name,
        scheduler=args.scheduler,
        seed=args.seed,
        light_semantics=args.light_semantics,
        plugins=plugins,
    )
    return session, f"{robots_path.name} → {pattern_path.name}, {args.scheduler}, seed {args.seed}"
