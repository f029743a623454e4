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
