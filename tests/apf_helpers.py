"""Shared helpers for the tests of the paper's algorithm."""

from __future__ import annotations

from apf_viz.algorithms import get_algorithm
from apf_viz.algorithms.apf_opaque_grid.audit import Audit, audit_run
from apf_viz.algorithms.apf_opaque_grid.resolutions import ALL
from apf_viz.core.engine import Engine


def line(k: int) -> list[tuple[int, int]]:
    return [(i, 0) for i in range(k)]


def without(*names: str) -> str:
    """The registry name of the algorithm with every resolution except these."""
    return "apf-opaque-grid@" + ",".join(sorted(ALL - set(names)))


def run(
    start,
    pattern=None,
    scheduler="fsync",
    seed=1,
    y_up=None,
    algorithm="apf-opaque-grid",
    light_semantics="compute",
    max_events=500_000,
) -> tuple[Engine, Audit, list[str]]:
    e = Engine(
        start,
        pattern or line(len(start)),
        get_algorithm(algorithm),
        y_up=y_up,
        max_events=max_events,
        light_semantics=light_semantics,
    )
    audit = audit_run(e, scheduler, seed)
    rules = [ev.rule or "" for ev in e.history.events() if ev.phase == "compute"]
    return e, audit, rules


def fired(rules: list[str], text: str) -> int:
    return sum(1 for r in rules if text in r)


def compare_on_the_collision_counterexample(session, twin: str = "apf-opaque-grid-literal"):
    """The collision counterexample's start, pattern and adversary (as a schedule) loaded into
    ``session``, with ``twin`` beside it in Compare; played to the end."""
    from pathlib import Path

    from apf_viz.core.formats import load_trace
    from apf_viz.core.schedule import schedule_of_trace, schedule_text

    demos = Path(__file__).resolve().parent.parent / "demo_patterns"
    session.load_robots("line.json", (demos / "starts" / "vertical-line-4.json").read_bytes())
    session.load_pattern("tee.json", (demos / "tee-4.json").read_bytes())
    _, events = load_trace(demos / "traces" / "literal-collision-4.jsonl")
    session.load_schedule("cex.jsonl", schedule_text(4, schedule_of_trace(events, False)).encode())
    session.compare_with(twin)
    while session.step():
        pass
    return session
