"""``apf-viz figure``: one moment of a run as a figure for a paper (SVG or TikZ), or the paper's own
figures (``demo_patterns/figures.json``) all at once."""

from __future__ import annotations

import argparse
from pathlib import Path

from apf_viz.cli.common import add_run_options, need_extra
from apf_viz.cli.sessions import start_session, trace_session
from apf_viz.core.files import check_writable, write_atomic
from apf_viz.core.formats import InputError
from apf_viz.core.schedulers import AUTOMATIC
from apf_viz.figure import FORMATS

NAME = "figure"
HELP = "one moment of a run (or the paper's figures) as SVG, TikZ or PNG, in grid units, with a legend"
OUTPUTS = ("out",)
"""The options naming files this command writes (never one of its inputs)."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--figure", help="one of the paper's figures by its label (demo_patterns/figures.json)")
    p.add_argument("--robots", type=Path, help="the start (a file, or a shipped name)")
    p.add_argument("--pattern", type=Path, help="the pattern (a file, or a shipped name)")
    p.add_argument("--trace", type=Path, help="a trace: the run it records (a file, or a shipped name)")
    p.add_argument("--event", type=int, help="the moment: after this many events (default: the start, or a "
                   "trace's end)")  # fmt: skip
    p.add_argument("--select", type=int, help="this robot's rays and the robots it cannot see")
    p.add_argument("--format", choices=FORMATS, default="svg", help="the figure's format")
    p.add_argument("--out", type=Path, help="write here (atomically) instead of standard output")
    p.add_argument("--caption", action="store_true",
                   help="write the caption into the figure (without: a bare picture for the paper's own "
                   "\\caption)")  # fmt: skip
    p.add_argument("--all-figures", type=Path, metavar="DIR",
                   help="write every figure of figures.json into DIR, as SVG and TikZ")  # fmt: skip
    add_run_options(p, AUTOMATIC)


def run(args: argparse.Namespace) -> int:
    from apf_viz.figure.export import figure_text, paper_figures

    if args.all_figures is not None:
        written = paper_figures(args.all_figures, caption=args.caption)
        print(f"apf-viz figure: {len(written)} files in {args.all_figures}")
        return 0
    if args.out is not None:
        check_writable(args.out)
    if args.format == "png":
        need_extra("figure --format png", ["matplotlib"])
        if args.out is None:
            raise InputError("--format png: give --out FILE (a picture is not written to the terminal)")
    session, caption = _session(args)
    caption = caption if args.caption else ""
    marked = _marked(args)
    if args.select is not None and not 0 <= args.select < len(session.robots):
        raise InputError(f"--select {args.select}: the run has robots 0 to {len(session.robots) - 1}")
    if args.format == "png":
        from apf_viz.core.files import replace_atomically
        from apf_viz.figure.export import figure_png

        data = figure_png(session, args.select, caption, marked)

        def write(tmp: str) -> None:
            Path(tmp).write_bytes(data)

        replace_atomically(args.out, write)
        print(f"apf-viz figure: {args.out}")
        return 0
    text = figure_text(session, args.format, args.select, caption, marked)
    if args.out is None:
        print(text, end="")
    else:
        write_atomic(args.out, text)
        print(f"apf-viz figure: {args.out}")
    return 0


def _marked(args: argparse.Namespace):
    """The robot a paper figure's caption names (marked in it), if the figure is one of the paper's."""
    if args.figure is None:
        return None
    from apf_viz.lecture import figures

    return figures()[args.figure].marked


def _session(args: argparse.Namespace):
    """The run at the moment asked for, and the figure's caption."""
    from apf_viz.figure.export import figure_session, run_to_event

    if args.figure is not None:
        return figure_session(args.figure)
    if args.trace is not None:
        session, name = trace_session(args.trace)
        run_to_event(session, args.event)
        return session, f"{name}, after {session.engine.state.events} events"
    if args.robots is None or args.pattern is None:
        raise InputError("figure: give --figure LABEL, --trace T, or --robots R with --pattern P")
    session, robots, _ = start_session(args)
    run_to_event(session, args.event or 0)
    events = session.engine.state.events
    return session, f"{robots}, {args.scheduler}, seed {args.seed}, after {events} events"
