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
    header, events = load_trace(trace)
    assert header.y_up is not None  # the run's flips (the demo file states none: drawn from --seed 2)
    assert out.read_text() == schedule_text(e.k, schedule_of_steps(e.history.steps), header.y_up, "compute")
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


HEADER = {"format": "apf-viz-schedule", "version": 2, "robots": 10, "y_up": [True] * 10}


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
        ([{"format": "apf-viz-trace", "version": 1, "robots": 10}], "s.jsonl: this is a trace, not a"),
        ([{"format": "apf-viz-schedul", "version": 2, "robots": 10}], "s.jsonl:1: format: Input should be"),
        ([{**HEADER, "robots": 4, "y_up": [True] * 4}], "a schedule for 4 robots, but the run has 10"),
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
    path.write_text(schedule_text(e.k, schedule_of_steps(e.history.steps), e.y_up, "compute"))
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
        list(follow(e, parse_schedule(json.dumps({**HEADER, "robots": 4, "y_up": [True] * 4}))))


def test_a_line_naming_a_robot_that_does_not_exist_keeps_the_run_up_to_it(tmp_path):
    path = write(tmp_path, [HEADER, {"robot": 0, "phase": "look"}, {"robot": 12, "phase": "look"}])
    trace = tmp_path / "so-far.jsonl"
    out = run_cli("run", "--robots", str(DEMO_START), "--pattern", str(DEMO_PATTERN), "--schedule", str(path),
                  "--trace", str(trace))  # fmt: skip
    assert out.returncode == 2 and "s.jsonl:3: robot 12 does not exist (10 robots)" in out.stderr
    assert [(e.robot, e.phase) for e in load_trace(trace)[1]] == [(0, "look")]
    wrong_header = write(
        tmp_path, [{**HEADER, "robots": 5, "y_up": [True] * 5}, {"robot": 7, "phase": "look"}]
    )
    out = run_cli("run", "--robots", str(DEMO_START), "--pattern", str(DEMO_PATTERN), "--schedule",
                  str(wrong_header))  # fmt: skip
    assert out.returncode == 2 and "a schedule for 5 robots, but the run has 10" in out.stderr


# ------------------------------------------------------------------------- a schedule is the whole adversary
CALL = Path(__file__).resolve().parent.parent / "demo_patterns" / "starts" / "sym-call-7.json"
CUP = Path(__file__).resolve().parent.parent / "demo_patterns" / "cup-7.json"


def run_json(*args: str) -> dict:
    out = run_cli("run", "--robots", str(CALL), "--pattern", str(CUP), "--json", *args)
    assert out.returncode in (0, 1), out.stderr
    return json.loads(out.stdout)


@pytest.mark.parametrize("algorithm", ["apf-opaque-grid", "apf-opaque-grid-literal"])
def test_a_recorded_schedule_replays_its_run_whatever_the_seed(tmp_path, algorithm):
    s = tmp_path / "s.jsonl"
    first = run_json(
        "--algorithm", algorithm, "--scheduler", "async", "--seed", "5", "--schedule-out", str(s)
    )
    header = json.loads(s.read_text().splitlines()[0])
    assert header["version"] == 2 and len(header["y_up"]) == 7 and header["light_semantics"] == "compute"
    for seed in ([], ["--seed", "1"], ["--seed", "99"]):
        again = run_json("--algorithm", algorithm, "--schedule", str(s), *seed)
        if first["outcome"] in ("formed", "stuck", "collision"):  # the literal paper may fail: the same way
            assert again["outcome"] == first["outcome"], (seed, again)
        assert {k: again[k] for k in ("final", "moves", "events")} == {
            k: first[k] for k in ("final", "moves", "events")
        }, seed


def test_the_schedule_flips_against_a_robots_file_that_states_its_own(tmp_path):
    s = tmp_path / "s.jsonl"
    run_json("--seed", "5", "--schedule-out", str(s))
    y_up = json.loads(s.read_text().splitlines()[0])["y_up"]
    robots = json.loads(CALL.read_text())
    same, other = tmp_path / "same.json", tmp_path / "other.json"
    same.write_text(json.dumps({**robots, "y_up": y_up}))
    other.write_text(json.dumps({**robots, "y_up": [not y_up[0], *y_up[1:]]}))
    base = ["run", "--pattern", str(CUP), "--schedule", str(s)]
    assert run_cli(*base, "--robots", str(same)).returncode == 0
    refused = run_cli(*base, "--robots", str(other))
    assert refused.returncode == 2 and refused.stderr.count("\n") == 1
    assert "robot 0" in refused.stderr and "--flips schedule or --flips file" in refused.stderr
    assert run_cli(*base, "--robots", str(other), "--flips", "schedule").returncode == 0
    with_file = run_cli(*base, "--robots", str(other), "--flips", "file", "--json")
    assert with_file.returncode in (0, 1) and with_file.stderr == ""


def test_schedule_with_scheduler_or_contradicting_semantics_is_refused(tmp_path):
    s = tmp_path / "s.jsonl"
    run_json("--light-semantics", "lc-atomic", "--schedule-out", str(s))
    base = ["run", "--robots", str(CALL), "--pattern", str(CUP), "--schedule", str(s)]
    out = run_cli(*base, "--scheduler", "ssync")
    assert out.returncode == 2 and "--then ssync" in out.stderr and out.stderr.count("\n") == 1
    out = run_cli(*base, "--light-semantics", "compute")
    assert out.returncode == 2 and "recorded under lc-atomic" in out.stderr
    assert run_cli(*base).returncode == 0  # the schedule's semantics, unasked
    assert run_cli(*base, "--light-semantics", "lc-atomic").returncode == 0


def test_a_version_1_schedule_loads_with_a_warning_that_the_seed_decides_the_flips(tmp_path):
    s = tmp_path / "v1.jsonl"
    s.write_text('{"format": "apf-viz-schedule", "version": 1, "robots": 7}\n{"robot": 0, "phase": "look"}\n')
    out = run_cli("run", "--robots", str(CALL), "--pattern", str(CUP), "--schedule", str(s), "--json")
    assert out.returncode == 1 and json.loads(out.stdout)["outcome"] == "schedule-end"
    assert "records no y-axis flips" in out.stderr and "--seed decides them" in out.stderr


def test_schedule_from_trace_writes_the_start_and_pattern_that_replay_the_run(tmp_path):
    trace, s, r, p = (tmp_path / n for n in ("t.jsonl", "s.jsonl", "r.json", "p.json"))
    first = run_cli(
        "run", "--robots", str(CALL), "--pattern", str(CUP), "--seed", "3", "--trace", str(trace), "--json"
    )
    made = run_cli(
        "schedule",
        "--from-trace",
        str(trace),
        "--out",
        str(s),
        "--robots-out",
        str(r),
        "--pattern-out",
        str(p),
    )
    assert made.returncode == 0, made.stderr
    again = run_cli("run", "--robots", str(r), "--pattern", str(p), "--schedule", str(s), "--json")
    assert again.returncode == 0 and again.stderr == ""
    assert json.loads(again.stdout)["final"] == json.loads(first.stdout)["final"]
    assert json.loads(again.stdout)["events"] == json.loads(first.stdout)["events"]


def test_a_schedule_given_as_a_trace_and_a_trace_given_as_a_schedule_say_which_command(tmp_path):
    s = tmp_path / "s.jsonl"
    run_json("--schedule-out", str(s))
    out = run_cli("replay", "--trace", str(s))
    assert (
        out.returncode == 2 and "this is a schedule, not a trace" in out.stderr and "--schedule" in out.stderr
    )
    trace = Path(__file__).parent / "gap_traces" / "L2.jsonl"
    out = run_cli("run", "--robots", str(CALL), "--pattern", str(CUP), "--schedule", str(trace))
    assert out.returncode == 2 and "this is a trace, not a schedule" in out.stderr


def test_the_visualiser_takes_an_uploaded_schedule_with_its_flips():
    from apf_viz.workbench.session import Session

    e = demo_engine()
    flipped = tuple(not u for u in e.y_up)
    other = Engine(e.start, e.pattern, get_algorithm("apf-opaque-grid"), y_up=flipped)
    advance(other, make_scheduler("async"), 3)
    text = schedule_text(other.k, schedule_of_steps(other.history.steps), other.y_up, "compute")
    session = Session(list(e.start), list(e.pattern), y_up=e.y_up)
    note = session.load_schedule("s.jsonl", text.encode())
    assert note is not None and "flips replace the run's (10 robots differ)" in note
    assert tuple(session.y_up) == flipped
    while session.engine.step_index < len(other.history.steps):
        session.step()
    assert session.engine.current_points() == other.current_points()


def test_a_schedule_line_carries_a_note_that_is_shown_when_it_is_played():
    from apf_viz.core.schedule import Activation, Round, parse_schedule, schedule_text
    from apf_viz.ui.app import demo_session

    s = demo_session()
    k = s.engine.k
    lines = [
        Activation(robot=0, phase="look", note="robot 0 looks first: it sees <everyone>"),
        Activation(robot=0, phase="compute"),
        Round(round=[1, 2], note="then a round"),
    ]
    text = schedule_text(k, lines)
    assert '"note": null' not in text and parse_schedule(text).notes == {2: lines[0].note, 4: "then a round"}
    s.load_schedule("notes.jsonl", text.encode())
    s.step()
    assert s.view().note_here == "robot 0 looks first: it sees <everyone>"
    s.step()
    assert s.view().note_here == ""  # a line without a note
    for _ in range(3):  # the round's Look, Compute and Move: its note on the step that ends it
        s.step()
    assert s.view().note_here == "then a round"
    too_long = '{"robot": 0, "phase": "look", "note": "' + "x" * 301 + '"}'
    with pytest.raises(InputError, match="note"):
        parse_schedule(text + too_long + "\n", "long.jsonl")


def test_a_followed_schedule_passes_nobody_over_as_its_replay_says(tmp_path):
    """``run --schedule`` and ``replay`` of its trace agree: a schedule chooses every activation, so no
    robot·step is passed over; the scheduler that goes on after it (``--then``) passes robots over."""
    demos = Path(__file__).resolve().parent.parent / "demo_patterns"
    lines = ['{"format": "apf-viz-schedule", "version": 1, "robots": 10}']
    lines += [json.dumps({"robot": r, "phase": p}) for r in (0, 1) for p in ("look", "compute", "move")]
    schedule = tmp_path / "six.jsonl"
    schedule.write_text("\n".join(lines) + "\n")
    trace = tmp_path / "six-trace.jsonl"
    files = ["--robots", str(demos / "starts" / "demo-10.json"), "--pattern", str(demos / "heart.json")]
    ran = run_cli("run", *files, "--schedule", str(schedule), "--trace", str(trace), "--json")
    replayed = run_cli("replay", "--trace", str(trace), "--json")
    assert json.loads(ran.stdout)["skipped"] == 0 == json.loads(replayed.stdout)["skipped"]
    then = run_cli("run", *files, "--schedule", str(schedule), "--then", "async", "--json")
    assert json.loads(then.stdout)["skipped"] > 0
