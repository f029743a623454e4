"""Verify in the browser: the explorer on the current run, in the background (workbench/verifier.py)."""

from __future__ import annotations

import threading

from apf_viz.core.formats import load_pattern, load_robots
from apf_viz.demos import demo_dir
from apf_viz.ui.app import demo_session
from apf_viz.workbench.run_config import RunConfig
from apf_viz.workbench.verifier import Verifier


def config_of(start: str, pattern: str, algorithm: str = "apf-opaque-grid") -> RunConfig:
    robots = load_robots(demo_dir() / "starts" / f"{start}.json")
    points = tuple(tuple(p) for p in load_pattern(demo_dir() / f"{pattern}.json").points)
    return RunConfig(tuple(tuple(p) for p in robots.robots), tuple(robots.flips(1)), points, algorithm)


def run(verifier: Verifier, config: RunConfig):
    assert verifier.start(config) is None
    verifier.wait(600)
    return verifier.status


def test_a_small_start_is_verified_with_its_state_count():
    seen = []
    status = run(Verifier(seen.append), config_of("one-on-L1-3", "corner-3"))
    assert status.state == "verified" and status.states > 100 and "verified:" in status.text
    assert seen[-1] == status


def test_the_literal_paper_on_the_vertical_line_is_a_violation_with_a_counterexample_the_session_follows():
    progress = []
    status = run(Verifier(progress.append), config_of("vertical-line-4", "tee-4", "apf-opaque-grid-literal"))
    assert status.state == "violation" and status.text.startswith("collision")
    assert any(p.state == "running" and p.states > 0 for p in progress)  # progress was reported
    s = demo_session()
    s.load_trace("counterexample.jsonl", status.trace.encode())
    while s.step():
        pass
    v = s.view()
    assert v.outcome == "collision" and v.collision is not None and "verdict: collision" in v.trace_note


def test_too_many_robots_is_refused_with_the_reason_and_cancel_stops_a_long_one():
    verifier = Verifier(lambda status: None)
    why = verifier.start(demo_session().config)
    assert why is not None and "k = 5" in why and "10" in why
    started = threading.Event()
    verifier = Verifier(lambda status: started.set())
    assert verifier.start(config_of("vertical-line-4", "tee-4", "apf-opaque-grid-literal")) is None
    assert (
        verifier.start(config_of("one-on-L1-3", "corner-3"))
        == "a verification is already running (Cancel it first)"
    )
    started.wait(120)
    verifier.cancel()
    verifier.wait(120)
    # The first progress report comes at 20,000 states, the violation at about 205,000.
    assert verifier.status.state == "cancelled" and verifier.status.text.startswith("cancelled")
