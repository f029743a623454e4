"""``apf-viz demos``: what ships, by the names the other commands accept."""

from __future__ import annotations

import argparse
from textwrap import shorten

from apf_viz.demos import demo_files, scenarios
from apf_viz.lecture import load_lecture

NAME = "demos"
HELP = "list what ships by name: Demo scenarios, lectures, starts, patterns, traces"


def add_arguments(p: argparse.ArgumentParser) -> None:
    pass


def run(args: argparse.Namespace) -> int:
    print("Demo scenarios (serve --demo TITLE, or a word naming one):")
    for title, scenario in scenarios().items():
        print(f"  {title} — {shorten(scenario.shows.split('. ')[0], 100, placeholder=' …')}")
    print("Lectures (serve --lecture NAME, lecture check NAME):")
    for stem, path in demo_files("lectures").items():
        lecture = load_lecture(path)
        print(f"  {stem} — {lecture.title}, {len(lecture.stops)} stops")
    print(f"Starts (--robots NAME): {', '.join(demo_files('starts'))}")
    print(f"Patterns (--pattern NAME): {', '.join(demo_files())}")
    print(f"Traces (--trace NAME): {', '.join(demo_files('traces', '.jsonl'))}")
    return 0
