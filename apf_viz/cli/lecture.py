"""``apf-viz lecture``: check a guided lecture."""

from __future__ import annotations

import argparse
from pathlib import Path

from apf_viz.cli.common import EXIT_NOT_FORMED

NAME = "lecture"
HELP = "check a guided lecture: run every stop headless, report each condition"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("action", choices=["check"], help="what to do with the lecture")
    p.add_argument(
        "file", type=Path, help="a lecture file (JSON), or a shipped lecture's name: algorithm-in-12-stops, …"
    )


def run(args: argparse.Namespace) -> int:
    """Every stop of the lecture in order, headless: its condition met or not, at which event; exit 1 if
    any was not (a lecturer checks the evening before)."""
    from apf_viz.lecture import find_lecture
    from apf_viz.workbench.lecturer import Lecturer
    from apf_viz.workbench.session import Session

    lecture = find_lecture(args.file)
    print(f"{args.file}: {lecture.title} — {len(lecture.stops)} stops", flush=True)
    failed = 0
    blank = Session([(0, 0)], [(0, 0)])  # the first stop loads its scenario (no viser is imported)
    for reached in Lecturer(blank, lecture).check():
        stop = lecture.stops[reached.index]
        where = "its scenario's start" if stop.scenario else "where the stop before left the run"
        until = stop.until.describe() if stop.until else where
        mark = "ok " if reached.holds else "NOT"
        note = f" — {reached.note}" if reached.note else ""
        claims = stop.expect.count() if stop.expect else 0
        said = f"; {claims} claim(s) hold" if claims and not reached.broken else ""
        span = f"to {until}; event {reached.event}{said}"
        print(f"  {mark} stop {reached.index + 1}: {stop.title} ({span}){note}")
        for broken in reached.broken:
            print(f"      {broken}")
        print(f"      shows: {reached.shown}")
        if stop.ask is not None and reached.answer is not None:
            a = reached.answer
            print(f"      asks: {stop.ask.words()} — the run answers {a.words()} (at event {a.event})")
        failed += not reached.holds
    held = len(lecture.stops) - failed
    print(f"{held} of {len(lecture.stops)} stops reached, their claims true", flush=True)
    return EXIT_NOT_FORMED if failed else 0
