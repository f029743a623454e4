"""Schedules: the adversary as a file (core/schedule.py), recorded, derived from traces, replayed against
any algorithm, and refused line by line when it cannot be followed."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from apf_viz.algorithms import get_algorithm
from apf_viz.algorithms.apf_opaque_grid.audit import audit_run
from apf_viz.core.engine import Engine
from apf_viz.core.formats import InputError, load_pattern, load_robots, load_trace
from apf_viz.core.run import advance
from apf_viz.core.schedule import (
    ScheduleError,
    follow,
    parse_schedule,
    schedule_of_steps,
    schedule_of_trace,
    schedule_text,
)
from apf_viz.core.schedulers import make_scheduler
from apf_viz.demos import DEMO_PATTERN, DEMO_START

GAP_TRACES = sorted((Path(__file__).parent / "gap_traces").glob("*.jsonl"))


def run_cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "apf_viz.cli", *args], capture_output=True, text=True)


def demo_engine(algorithm: str = "apf-opaque-grid", semantics: str = "compute") -> Engine:
    robots, pattern = load_robots(DEMO_START), load_pattern(DEMO_PATTERN)
    return Engine(
        [tuple(p) for p in robots.robots],
        [tuple(p) for p in pattern.points],
        get_algorithm(algorithm),
        y_up=robots.flips(1),
        light_semantics=semantics,
    )


@pytest.mark.parametrize("scheduler", ["async", "stale-first", "ssync", "fsync"])
@pytest.mark.parametrize("semantics", ["compute", "lc-atomic"])
def test_a_recorded_schedule_replays_the_same_events_and_final_configuration(scheduler, semantics):
    e = demo_engine(semantics=semantics)
    advance(e, make_scheduler(scheduler), 4)
    text = schedule_text(e.k, schedule_of_steps(e.history.steps))
    again = demo_engine(semantics=semantics)
    list(follow(again, parse_schedule(text)))
    assert again.history.events() == e.history.events()
    assert again.current_points() == e.current_points() and again.outcome == e.outcome == "formed"


def test_the_schedule_of_a_trace_is_the_schedule_of_its_run(tmp_path):
    e = demo_engine()
    advance(e, make_scheduler("async"), 2)
    trace = tmp_path / "t.jsonl"
    out = tmp_path / "s.jsonl"
    assert run_cli("run", "--robots", str(DEMO_START), "--pattern", str(DEMO_PATTERN), "--seed", "2",
                   "--trace", str(trace)).returncode == 0  # fmt: skip
    assert run_cli("schedule", "--from-trace", str(trace), "--out", str(out)).returncode == 0
    assert out.read_text() == schedule_text(e.k, schedule_of_steps(e.history.steps))
    header, events = load_trace(trace)
    assert schedule_of_trace(events, False) == schedule_of_steps(e.history.steps)


@pytest.mark.parametrize("path", GAP_TRACES, ids=[p.stem for p in GAP_TRACES])
def test_each_gap_schedule_breaks_its_ablated_variant_and_the_default_forms(path):
    header, events = load_trace(path)
    schedule = parse_schedule(schedule_text(len(header.robots), schedule_of_trace(events, False)))

    def engine(algorithm: str, max_events: int | None) -> Engine:
        return Engine(
            [tuple(p) for p in header.robots],
            [tuple(p) for p in header.pattern],
            get_algorithm(algorithm),
            y_up=header.y_up,
            light_semantics=header.light_semantics,
            max_events=max_events,
        )

    ablated = engine(header.algorithm, len(events))
    list(follow(ablated, schedule))
    two_leaders = ablated.state.lights.count("leader") > 1
    assert ablated.outcome in ("collision", "stuck", "limit") or two_leaders, ablated.outcome
    fixed = engine("apf-opaque-grid", 500_000)
    for _ in follow(fixed, schedule):
        assert fixed.outcome != "collision" and fixed.state.lights.count("leader") <= 1
    audit = audit_run(fixed, "async", 1)  # then the ASYNC scheduler (--then async)
    assert audit.ok and fixed.outcome == "formed", audit.problems


def write(tmp_path: Path, lines: list) -> Path:
    path = tmp_path / "s.jsonl"
    path.write_text("\n".join(line if isinstance(line, str) else json.dumps(line) for line in lines) + "\n")
    return path


HEADER = {"format": "apf-viz-schedule", "version": 1, "robots": 10}


@pytest.mark.parametrize(
    "lines, message",
    [
        ([HEADER, {"robot": 12, "phase": "look"}], "s.jsonl:2: robot 12 does not exist (10 robots)"),
        ([HEADER, {"robot": 0, "phase": "look"}, {"robot": 0, "phase": "move"}],
         "s.jsonl:3: robot 0's next phase is compute, not move"),
        ([HEADER, {"robot": 1, "phase": "look"}, {"round": [1, 2]}],
         "s.jsonl:3: a round starts with its robots idle; robot 1's next phase is compute"),
        ([HEADER, "{not json"], "s.jsonl:2: not valid JSON"),
        ([HEADER, {"robot": 0, "phase": "jump"}], "s.jsonl:2: phase: Input should be 'look', 'compute'"),
        ([HEADER, {"round": [3, 3]}], "s.jsonl:2: a robot is listed twice in one round"),
        ([{"format": "apf-viz-trace", "version": 1, "robots": 10}], "s.jsonl:1: format: Input should be"),
        ([{**HEADER, "robots": 4}], "a schedule for 4 robots, but the run has 10"),
        ([], "empty schedule file"),
    ],
)  # fmt: skip
def test_a_schedule_that_cannot_be_followed_is_one_line_exit_2_naming_the_line(tmp_path, lines, message):
    path = write(tmp_path, lines)
    trace = tmp_path / "so-far.jsonl"
    out = run_cli("run", "--robots", str(DEMO_START), "--pattern", str(DEMO_PATTERN), "--schedule", str(path),
                  "--trace", str(trace))  # fmt: skip
    assert out.returncode == 2 and message in out.stderr and out.stderr.count("\n") == 1, out.stderr
    assert "Traceback" not in out.stderr


def test_the_run_so_far_is_kept_when_a_line_cannot_be_followed(tmp_path):
    path = write(tmp_path, [HEADER, {"robot": 0, "phase": "look"}, {"robot": 0, "phase": "compute"},
                            {"robot": 0, "phase": "look"}])  # fmt: skip
    trace = tmp_path / "so-far.jsonl"
    out = run_cli("run", "--robots", str(DEMO_START), "--pattern", str(DEMO_PATTERN), "--schedule", str(path),
                  "--trace", str(trace))  # fmt: skip
    assert out.returncode == 2 and "s.jsonl:4: robot 0's next phase is move, not look" in out.stderr
    header, events = load_trace(trace)
    assert [(e.robot, e.phase) for e in events] == [(0, "look"), (0, "compute")]


def test_a_schedule_ends_the_run_or_hands_over_to_then(tmp_path):
    e = demo_engine()
    advance(e, make_scheduler("async"), 4, steps=40)
    path = tmp_path / "s.jsonl"
    path.write_text(schedule_text(e.k, schedule_of_steps(e.history.steps)))
    base = [
        "run",
        "--robots",
        str(DEMO_START),
        "--pattern",
        str(DEMO_PATTERN),
        "--schedule",
        str(path),
        "--json",
    ]
    ended = run_cli(*base)
    data = json.loads(ended.stdout)
    assert ended.returncode == 1 and data["outcome"] == "schedule-end" and data["events"] == e.state.events
    then = run_cli(*base, "--then", "async")
    assert then.returncode == 0 and json.loads(then.stdout)["outcome"] == "formed"
    alone = run_cli("run", "--robots", str(DEMO_START), "--pattern", str(DEMO_PATTERN), "--then", "async")
    assert alone.returncode == 2 and "--then continues after a --schedule" in alone.stderr


def test_follow_refuses_before_it_changes_anything():
    e = demo_engine()
    with pytest.raises(ScheduleError, match="next phase is look, not move"):
        list(follow(e, parse_schedule(schedule_text(10, []) + '{"robot": 3, "phase": "move"}\n')))
    assert e.state.events == 0
    with pytest.raises(InputError, match="for 4 robots"):
        list(follow(e, parse_schedule(json.dumps({**HEADER, "robots": 4}))))


def test_a_line_naming_a_robot_that_does_not_exist_keeps_the_run_up_to_it(tmp_path):
    path = write(tmp_path, [HEADER, {"robot": 0, "phase": "look"}, {"robot": 12, "phase": "look"}])
    trace = tmp_path / "so-far.jsonl"
    out = run_cli("run", "--robots", str(DEMO_START), "--pattern", str(DEMO_PATTERN), "--schedule", str(path),
                  "--trace", str(trace))  # fmt: skip
    assert out.returncode == 2 and "s.jsonl:3: robot 12 does not exist (10 robots)" in out.stderr
    assert [(e.robot, e.phase) for e in load_trace(trace)[1]] == [(0, "look")]
    wrong_header = write(tmp_path, [{**HEADER, "robots": 5}, {"robot": 7, "phase": "look"}])
    out = run_cli("run", "--robots", str(DEMO_START), "--pattern", str(DEMO_PATTERN), "--schedule",
                  str(wrong_header))  # fmt: skip
    assert out.returncode == 2 and "a schedule for 5 robots, but the run has 10" in out.stderr
