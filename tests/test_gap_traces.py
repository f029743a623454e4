"""Each saved trace shows why one resolution is needed: with every resolution *except* that one the run
fails (replayed exactly, event by event); the same schedule with all resolutions does not fail."""

from __future__ import annotations

from pathlib import Path

import pytest

from apf_viz.algorithms import get_algorithm
from apf_viz.algorithms.apf_opaque_grid.audit import audit_run
from apf_viz.core.engine import Engine
from apf_viz.core.formats import load_trace
from apf_viz.core.run import engine_for_trace, replay

TRACES = sorted((Path(__file__).parent / "gap_traces").glob("*.jsonl"))


def engine_for(header, algorithm: str, max_events: int | None = None) -> Engine:
    return engine_for_trace(header, get_algorithm(algorithm), max_events)


@pytest.mark.parametrize("path", TRACES, ids=[p.stem for p in TRACES])
def test_the_trace_replays_to_its_failure_without_the_resolution(path):
    header, events = load_trace(path)
    gap = header.options["shows_gap"]
    assert gap == path.stem and gap not in header.algorithm.split("@")[1].split(",")
    e = engine_for(header, header.algorithm, max_events=len(events))
    replay(e, events, str(path))
    failed = e.outcome in ("collision", "stuck", "limit") or e.state.lights.count("leader") > 1
    assert failed, e.outcome
    assert e.outcome != "formed"


@pytest.mark.parametrize("path", TRACES, ids=[p.stem for p in TRACES])
def test_the_same_schedule_with_every_resolution_forms_the_pattern(path):
    header, events = load_trace(path)
    recorded = engine_for(header, header.algorithm, max_events=len(events))
    replay(recorded, events, str(path))
    fixed = engine_for(header, "apf-opaque-grid", max_events=500_000)
    for step in recorded.history.steps:
        if fixed.finished:
            break
        fixed.step(step.record.robots, round=step.record.round)
        assert fixed.outcome != "collision" and fixed.state.lights.count("leader") <= 1
    audit = audit_run(fixed, "async", 1)
    assert audit.ok, audit.problems


def test_there_is_a_trace_for_the_resolutions_random_search_found_needed():
    assert {p.stem for p in TRACES} >= {
        "E2",
        "G1",
        "G2",
        "G3",
        "KD",
        "LA",
        "LW",
        "N2",
        "P3",
        "SD",
        "L2",
        "G4",
        "G5",
    }


LITERAL = sorted((Path(__file__).parent / "literal_traces").glob("*.jsonl"))


@pytest.mark.parametrize("path", LITERAL, ids=[p.stem for p in LITERAL])
def test_the_literal_papers_failures_replay(path):
    header, events = load_trace(path)
    assert header.algorithm == "apf-opaque-grid-literal"
    e = engine_for(header, header.algorithm, max_events=len(events))
    replay(e, events, str(path))
    expected = {"collision": "collision", "deadlock": "stuck", "livelock": "limit"}[path.stem]
    assert e.outcome == expected
