"""``apf-viz lecture``: check a guided lecture."""

from __future__ import annotations

import argparse
from pathlib import Path

from apf_viz.cli.common import EXIT_NOT_FORMED

NAME = "lecture"
HELP = (
    "check a guided lecture (run every stop headless, report each condition); write one: the rule ids "
    "(rules) and a start's robot numbers, lights and mirror axis (show)"
)


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "action",
        choices=["check", "rules", "show"],
        help="check a lecture; list the rule ids a stop's until.rule names; show a start as a stop sees it",
    )
    p.add_argument(
        "file",
        type=Path,
        nargs="?",
        help="check: a lecture file (JSON), or a shipped lecture's name (algorithm-in-12-stops, …); show: a "
        "Demo scenario's name (as a stop's scenario says it), or a robots file or shipped start",
    )
    p.add_argument("--pattern", type=Path, help="show, a robots file: its pattern (a file or shipped name)")
    p.add_argument("--algorithm", default=None, help="rules, show: the algorithm (a registry name)")


def run(args: argparse.Namespace) -> int:
    from apf_viz.core.formats import InputError

    if args.action == "rules":
        return _rules(args)
    if args.file is None:
        raise InputError(f"lecture {args.action}: name a {'lecture' if args.action == 'check' else 'start'}")
    if args.action == "show":
        return _show(args)
    return _check(args)


def _rules(args: argparse.Namespace) -> int:
    from apf_viz.algorithms import DEFAULT_ALGORITHM, get_algorithm
    from apf_viz.workbench.start_sheet import rules_sheet

    print(rules_sheet(get_algorithm(args.algorithm or DEFAULT_ALGORITHM)))
    return 0


def _show(args: argparse.Namespace) -> int:
    """A start as a lecture's stops see it: a Demo scenario (its own algorithm), or robots with a pattern."""
    from apf_viz.demos import scenarios
    from apf_viz.workbench.session import Session
    from apf_viz.workbench.start_sheet import start_sheet

    name = str(args.file)
    session = Session([(0, 0)], [(0, 0)])
    if name in scenarios():
        session.load_scenario(name)
        if args.algorithm:
            session.set_algorithm(args.algorithm)
        print(start_sheet(session, f"scenario {name!r}"))
        return 0
    from apf_viz.algorithms import DEFAULT_ALGORITHM
    from apf_viz.api.inputs import start_of
    from apf_viz.core.formats import InputError

    if args.pattern is None:
        raise InputError(f"{name}: not a Demo scenario; for a robots file give --pattern too")
    start = start_of(args.file, args.pattern)
    session = Session(
        start.robots, start.pattern, y_up=start.flips(1), algorithm=args.algorithm or DEFAULT_ALGORITHM
    )
    print(start_sheet(session, start.robots_name))
    return 0


def _check(args: argparse.Namespace) -> int:
    """Every stop of the lecture in order, headless: its condition met or not, at which event; exit 1 if
    any was not (a lecturer checks the evening before)."""
    from apf_viz.api.lectures import lecture_check
    from apf_viz.lecture import find_lecture

    lecture = find_lecture(args.file)  # refused in one line before anything is said
    print(f"{args.file}: {lecture.title} — {len(lecture.stops)} stops", flush=True)
    checked = lecture_check(args.file)
    for stop in checked.stops:
        mark = "ok " if stop.holds else "NOT"
        note = f" — {stop.note}" if stop.note else ""
        said = f"; {stop.claims} claim(s) hold" if stop.claims and not stop.broken else ""
        print(f"  {mark} stop {stop.number}: {stop.title} (to {stop.until}; event {stop.event}{said}){note}")
        for broken in stop.broken:
            print(f"      {broken}")
        print(f"      shows: {stop.shown}")
        if stop.asks is not None and stop.answer is not None:
            print(f"      asks: {stop.asks} — the run answers {stop.answer} (at event {stop.answer_event})")
    held = sum(stop.holds for stop in checked.stops)
    print(f"{held} of {len(checked.stops)} stops reached, their claims true", flush=True)
    return EXIT_NOT_FORMED if held < len(checked.stops) else 0
