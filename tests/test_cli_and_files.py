"""Files and CLI: every malformed input is one line naming the file and the problem, exit code 2."""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path

import pytest

from apf_viz.cli import main
from apf_viz.core.files import write_atomic
from apf_viz.core.formats import InputError, load_trace
from apf_viz.core.symmetry import unsolvable_axis

GOOD_ROBOTS = {"robots": [[0, 0], [3, 0], [5, 0], [2, 2], [6, 2]]}
GOOD_PATTERN = {"points": [[0, 0], [1, 0], [2, 0], [0, 2], [1, 2]]}


def run_cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "apf_viz.cli", *args], capture_output=True, text=True)


BAD_ROBOTS = [
    ("not json", "{robots: [[0,0]]", "not valid JSON"),
    ("wrong shape", {"robot": [[0, 0]]}, "robots: Field required"),
    ("not a list", {"robots": 3}, "robots"),
    ("non-integer", {"robots": [[0, 0], [1, 0.5]]}, "robots[1][1]: Input should be a valid integer"),
    ("string coordinate", {"robots": [[0, "1"]]}, "valid integer"),
    ("three coordinates", {"robots": [[0, 0, 0]]}, "robots[0]"),
    ("duplicate", {"robots": [[0, 0], [1, 1], [0, 0]]}, "duplicate robot at (0, 0)"),
    ("y_up length", {"robots": [[0, 0], [1, 1]], "y_up": [True]}, "y_up has 1 entries for 2 robots"),
    ("y_up not bool", {"robots": [[0, 0]], "y_up": ["yes"]}, "y_up[0]"),
    ("empty", {"robots": []}, "at least 1"),
]


@pytest.mark.parametrize(("case", "data", "message"), BAD_ROBOTS, ids=[c[0] for c in BAD_ROBOTS])
def test_malformed_robots_file(write_json, case, data, message):
    robots = write_json("r.json", data)
    pattern = write_json("p.json", GOOD_PATTERN)
    proc = run_cli("run", "--robots", str(robots), "--pattern", str(pattern))
    assert proc.returncode == 2
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1, proc.stderr
    assert str(robots) in lines[0] and message in lines[0]
    assert "Traceback" not in proc.stderr


BAD_PATTERNS = [
    ("not json", "[1, 2", "not valid JSON"),
    ("duplicate", {"points": [[0, 0], [0, 0], [1, 0], [2, 0], [3, 0]]}, "duplicate pattern point at (0, 0)"),
    ("wrong size", {"points": [[0, 0], [1, 0]]}, "the pattern has 2 points but there are 5 robots"),
    ("unknown field", {"points": [[0, 0]], "colour": "red"}, "colour"),
]


@pytest.mark.parametrize(("case", "data", "message"), BAD_PATTERNS, ids=[c[0] for c in BAD_PATTERNS])
def test_malformed_pattern_file(write_json, case, data, message):
    robots = write_json("r.json", GOOD_ROBOTS)
    pattern = write_json("p.json", data)
    proc = run_cli("run", "--robots", str(robots), "--pattern", str(pattern))
    assert proc.returncode == 2
    assert proc.stderr.count("\n") == 1 and str(pattern) in proc.stderr and message in proc.stderr


def test_missing_file_and_unknown_algorithm(write_json, tmp_path):
    pattern = write_json("p.json", GOOD_PATTERN)
    proc = run_cli("run", "--robots", str(tmp_path / "nope.json"), "--pattern", str(pattern))
    assert proc.returncode == 2 and "no such file" in proc.stderr
    robots = write_json("r.json", GOOD_ROBOTS)
    proc = run_cli("run", "--robots", str(robots), "--pattern", str(pattern), "--algorithm", "nope")
    assert proc.returncode == 2 and "unknown algorithm 'nope'" in proc.stderr


def test_malformed_traces(write_json):
    header = {
        "format": "apf-viz-trace",
        "version": 1,
        "robots": [[0, 0], [1, 0]],
        "pattern": [[0, 0], [0, 1]],
        "scheduler": "async",
        "seed": 1,
        "algorithm": "stay",
    }
    cases = [
        ("", "empty trace"),
        (json.dumps({**header, "format": "other"}), "format"),
        (json.dumps(header) + '\n{"robot": 5, "phase": "look", "sees": []}', "robot 5 does not exist"),
        (json.dumps(header) + '\n{"robot": 0, "phase": "look"}', "a look event needs 'sees'"),
        (json.dumps(header) + "\n{oops", "not valid JSON"),
        (
            json.dumps(header) + '\n{"robot": 0, "phase": "compute", "light": "off", "move": null}',
            "robot 0 cannot compute now, its next event is look",
        ),
        (json.dumps(header) + '\n{"robot": 0, "phase": "look", "sees": []}', "differs on replay"),
    ]
    for text, message in cases:
        path = write_json("t.jsonl", text)
        proc = run_cli("replay", "--trace", str(path))
        assert proc.returncode == 2, (text, proc.stderr)
        assert proc.stderr.count("\n") == 1 and message in proc.stderr, proc.stderr


def test_run_json_output_trace_and_replay(write_json, tmp_path, capsys):
    robots = write_json("r.json", GOOD_ROBOTS)
    pattern = write_json("p.json", GOOD_PATTERN)
    trace = tmp_path / "t.jsonl"
    code = main(
        [
            "run",
            "--robots",
            str(robots),
            "--pattern",
            str(pattern),
            "--json",
            "--trace",
            str(trace),
            "--seed",
            "5",
            "--scheduler",
            "stale-first",
            "--algorithm",
            "compact-left",
        ]
    )
    out = json.loads(capsys.readouterr().out)
    assert code == 0 and out["outcome"] == "formed"
    assert set(out) == {
        "outcome", "final", "k", "D", "moves", "events", "cycles", "skipped", "moves_per_kD", "max_moves",
        "max_events", "lights_used", "max_recorded",
    }  # fmt: skip
    assert (out["k"], out["D"]) == (5, 7) and out["max_moves"] == 50 * 5 * 7  # D: the start is 7 wide
    assert out["final"] == [[0, 0], [1, 0], [2, 0], [0, 2], [1, 2]]
    header, events = load_trace(trace)
    assert header.scheduler == "stale-first" and header.seed == 5 and len(events) == out["events"]
    assert main(["replay", "--trace", str(trace), "--json"]) == 0
    replayed = json.loads(capsys.readouterr().out)
    run_only = ("skipped", "max_moves", "max_events")  # a replay applies steps: no skipping, no caps
    assert {k: v for k, v in replayed.items() if k not in run_only} == {
        k: v for k, v in out.items() if k not in run_only
    }


def test_not_formed_exits_1(write_json, capsys):
    robots = write_json("r.json", GOOD_ROBOTS)
    pattern = write_json("p.json", {"points": [[0, 0], [0, 1], [0, 2], [0, 3], [0, 4]]})
    assert (
        main(
            [
                "run",
                "--robots",
                str(robots),
                "--pattern",
                str(pattern),
                "--json",
                "--algorithm",
                "compact-left",
            ]
        )
        == 1
    )
    assert json.loads(capsys.readouterr().out)["outcome"] == "stuck"


def test_unsolvable_start_exits_3_naming_the_axis(write_json):
    robots = write_json("r.json", {"robots": [[0, 0], [0, 3], [2, 1], [2, 2]]})
    pattern = write_json("p.json", {"points": [[0, 0], [1, 0], [2, 0], [3, 0]]})
    proc = run_cli("run", "--robots", str(robots), "--pattern", str(pattern), "--json")
    assert proc.returncode == 3
    assert "y = 1.5" in proc.stderr and json.loads(proc.stdout)["outcome"] == "unsolvable"
    forced = run_cli(
        "run", "--robots", str(robots), "--pattern", str(pattern), "--force", "--max-events", "500"
    )
    assert forced.returncode in (0, 1)


def test_theorem_1_axis():
    assert unsolvable_axis([(0, 0), (0, 1)]) == 0.5
    assert unsolvable_axis([(0, 0), (0, 2)]) == 1
    assert unsolvable_axis([(0, 0), (0, 1), (0, 2)]) is None  # the axis passes through a robot
    assert unsolvable_axis([(0, 0), (1, 2)]) is None  # not symmetric
    assert unsolvable_axis([(0, 0)]) is None
    assert unsolvable_axis([(0, 0), (2, 0)]) is None  # the axis y = 0 passes through both


def test_random_robots(tmp_path):
    out = tmp_path / "r.json"
    assert (
        main(
            [
                "random-robots",
                "--count",
                "6",
                "--width",
                "4",
                "--height",
                "3",
                "--seed",
                "2",
                "--out",
                str(out),
            ]
        )
        == 0
    )
    pts = [tuple(p) for p in json.loads(out.read_text())["robots"]]
    assert len(set(pts)) == 6 and all(0 <= x < 4 and 0 <= y < 3 for x, y in pts)
    assert unsolvable_axis(pts) is None
    again = run_cli("random-robots", "--count", "6", "--width", "4", "--height", "3", "--seed", "2")
    assert [tuple(p) for p in json.loads(again.stdout)["robots"]] == pts
    too_many = run_cli("random-robots", "--count", "20", "--width", "4", "--height", "3")
    assert too_many.returncode == 2 and "do not fit" in too_many.stderr


def test_bad_option_is_one_line_exit_2(write_json):
    proc = run_cli("run", "--robots", "a", "--pattern", "b", "--scheduler", "chaos")
    assert proc.returncode == 2 and proc.stderr.count("\n") == 1 and "chaos" in proc.stderr


def test_write_atomic_leaves_the_old_file_on_failure(tmp_path, monkeypatch):
    target = tmp_path / "keep.json"
    target.write_text("old")

    def boom(*a, **k):
        raise OSError("disk full")

    monkeypatch.setattr("os.replace", boom)
    with pytest.raises(OSError):
        write_atomic(target, "new")
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["keep.json"]


def test_help_documents_every_command():
    out = run_cli("--help").stdout + run_cli("run", "--help").stdout
    for word in (
        "run",
        "replay",
        "random-robots",
        "serve",
        "--scheduler",
        "--trace",
        "--json",
        "--force",
        "Exit codes",
    ):
        assert word in out


def test_input_error_is_a_value_error():
    assert issubclass(InputError, ValueError)
    assert Path  # keeps the import used in type hints


# ---------------------------------------------------------------------------------------------- hardening
def one_line_error(proc: subprocess.CompletedProcess, *parts: str) -> None:
    assert proc.returncode == 2, (proc.returncode, proc.stderr)
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in proc.stderr, proc.stderr
    for part in parts:
        assert part in lines[0], (part, lines[0])


def test_coordinates_beyond_the_range_are_one_line_errors_in_run_and_replay(write_json):
    robots = write_json("r.json", '{"robots": [[0, 0], [100000000000000000000000, 1]]}')
    pattern = write_json("p.json", {"points": [[0, 0], [1, 0]]})
    one_line_error(
        run_cli("run", "--robots", str(robots), "--pattern", str(pattern)),
        str(robots),
        "robot 1 at (~10^23, 1)",
        "1,000,000,000,000",
    )
    header = {
        "format": "apf-viz-trace",
        "version": 1,
        "robots": [[0, 0], [0, 2**63 - 1]],
        "pattern": [[0, 0], [1, 0]],
        "scheduler": "async",
        "algorithm": "stay",
    }
    trace = write_json("t.jsonl", json.dumps(header) + "\n")
    one_line_error(run_cli("replay", "--trace", str(trace)), str(trace), "robot 1 at (0, ~10^18)")


def test_replay_refuses_a_pattern_of_the_wrong_size(write_json):
    header = {
        "format": "apf-viz-trace",
        "version": 1,
        "robots": [[0, 0], [1, 0], [2, 2]],
        "pattern": [[0, 0], [1, 0]],
        "scheduler": "async",
        "algorithm": "stay",
    }
    trace = write_json("t.jsonl", json.dumps(header) + "\n")
    one_line_error(
        run_cli("replay", "--trace", str(trace)),
        str(trace),
        "the pattern has 2 points but there are 3 robots",
    )


@pytest.mark.parametrize("value", ["0", "-5", "many"])
def test_event_and_state_limits_must_be_positive(write_json, value):
    robots = write_json("r.json", GOOD_ROBOTS)
    pattern = write_json("p.json", GOOD_PATTERN)
    one_line_error(
        run_cli("run", "--robots", str(robots), "--pattern", str(pattern), "--max-events", value),
        "--max-events",
    )
    one_line_error(
        run_cli("check", "--robots", str(robots), "--pattern", str(pattern), "--max-states", value),
        "--max-states",
    )


def test_a_bad_output_path_is_refused_before_any_work(write_json, tmp_path):
    robots = write_json("r.json", GOOD_ROBOTS)
    pattern = write_json("p.json", GOOD_PATTERN)
    bad = tmp_path / "no-such-folder" / "run.jsonl"
    proc = run_cli("run", "--robots", str(robots), "--pattern", str(pattern), "--trace", str(bad))
    one_line_error(proc, str(bad), "does not exist")
    assert proc.stdout == ""  # no run happened: its summary was never printed
    assert ".tmp" not in proc.stderr  # names the user's path, not a temporary file
    one_line_error(
        run_cli("run", "--robots", str(robots), "--pattern", str(pattern), "--trace", str(tmp_path)),
        str(tmp_path),
        "is a directory",
    )
    one_line_error(
        run_cli("random-robots", "--count", "3", "--width", "5", "--height", "5", "--out", str(bad)), str(bad)
    )
    one_line_error(
        run_cli("check", "--robots", str(robots), "--pattern", str(pattern), "--counterexample", str(bad)),
        str(bad),
    )


def test_a_start_that_is_the_pattern_is_formed_at_time_0_even_when_symmetric(write_json):
    # Mirror-symmetric about y = 0.5, a line through no robot: Theorem 1 would call it unsolvable.
    robots = write_json("r.json", {"robots": [[0, 0], [0, 1], [2, 0], [2, 1]]})
    pattern = write_json("p.json", {"points": [[5, 5], [5, 6], [7, 5], [7, 6]]})
    proc = run_cli("run", "--robots", str(robots), "--pattern", str(pattern), "--json")
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout)
    assert (out["outcome"], out["moves"], out["events"]) == ("formed", 0, 0)
    check = run_cli("check", "--robots", str(robots), "--pattern", str(pattern), "--json", "--flips", "all")
    assert check.returncode == 0 and json.loads(check.stdout)["verdict"] == "verified", check.stderr
    other = write_json("q.json", {"points": [[0, 0], [1, 0], [2, 0], [3, 0]]})
    unsolvable = run_cli("run", "--robots", str(robots), "--pattern", str(other))
    assert unsolvable.returncode == 3  # not the pattern: still unsolvable


def test_random_robots_in_a_huge_box_builds_only_the_drawn_cells():
    """Today every cell of the box was built first (4.6 GB for 100,000 × 100,000): run it with 300 MB of
    address space beyond what the interpreter has at start, so building the box fails loudly."""
    code = (
        "import resource, sys\n"
        "from apf_viz.cli import main\n"
        "import apf_viz.core.random_configs, apf_viz.core.symmetry\n"
        "soft, hard = resource.getrlimit(resource.RLIMIT_AS)\n"
        "used = int(open('/proc/self/statm').read().split()[0]) * resource.getpagesize()\n"
        "resource.setrlimit(resource.RLIMIT_AS, (used + 300 * 2**20, hard))\n"
        "sys.exit(main(['random-robots', '--count', '3', '--width', '100000', '--height', '100000']))\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr[-500:]
    points = json.loads(proc.stdout)["robots"]
    assert len(points) == 3 and all(0 <= x < 100_000 and 0 <= y < 100_000 for x, y in points)
    one_line_error(
        run_cli("random-robots", "--count", "3", "--width", str(10**13), "--height", "5"), "--width"
    )
    one_line_error(run_cli("random-robots", "--count", "0", "--width", "5", "--height", "5"), "--count")


def test_random_pattern(tmp_path):
    out = tmp_path / "p.json"
    args = ["random-pattern", "--count", "7", "--width", "4", "--height", "4", "--seed", "3", "--name", "r7"]
    assert main([*args, "--out", str(out)]) == 0
    data = json.loads(out.read_text())
    assert data["name"] == "r7" and len({tuple(p) for p in data["points"]}) == 7
    assert json.loads(run_cli(*args).stdout) == data  # the same seed draws the same pattern
    one_line_error(run_cli("random-pattern", "--count", "17", "--width", "4", "--height", "4"), "do not fit")


def test_every_option_of_every_command_has_help_and_shows_its_default(monkeypatch):
    from apf_viz.cli import build_parser

    monkeypatch.setenv("COLUMNS", "400")  # no line wrapping inside a default
    parser = build_parser()
    commands = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction)).choices
    assert {"run", "replay", "random-robots", "random-pattern", "check", "serve"} <= set(commands)
    for name, sub in commands.items():
        text = sub.format_help()
        for action in sub._actions:
            if not action.option_strings or action.dest == "help":
                continue
            assert action.help, f"{name} {action.option_strings[0]} has no help"
            if action.default not in (None, False):
                flag = action.option_strings[0]
                after = " ".join(text.split(flag, 2)[-1].split())
                assert f"(default: {action.default})" in after, f"{name} {flag} hides its default"
                assert "(default" not in action.help, f"{name} {flag} says its default twice"
    serve = commands["serve"].format_help()
    for word in ("--scheduler", "--seed", "apf-opaque-grid-literal", "compact-left", "--algorithm"):
        assert word in serve


def test_a_robots_file_without_y_up_gets_the_same_flips_everywhere(write_json, tmp_path):
    from apf_viz.cli.serve import session_config
    from apf_viz.core.frames import random_y_up
    from apf_viz.workbench.config import session_from_config
    from apf_viz.workbench.session import Session

    start = [[0, 0], [3, 0], [5, 1], [2, 2], [6, 2], [1, 4], [4, 5]]
    robots = write_json("r.json", {"robots": start})
    pattern = write_json("p.json", {"points": [[x, 0] for x in range(7)]})
    seed = 11
    expected = random_y_up(7, seed)
    assert len(set(expected)) == 2  # a real mixture, so "all up" would differ
    trace = tmp_path / "t.jsonl"
    run = ["run", "--robots", str(robots), "--pattern", str(pattern), "--seed", str(seed)]
    assert run_cli(*run, "--trace", str(trace), "--max-events", "10").returncode in (0, 1)
    assert load_trace(trace)[0].y_up == expected
    check = run_cli("check", *run[1:], "--json", "--max-states", "10")
    assert json.loads(check.stdout)["y_up"] == expected, check.stderr
    args = build_serve_args(robots, pattern, seed)
    assert session_from_config(session_config(args)).y_up == expected
    session = Session([(0, y) for y in range(7)], [(x, 0) for x in range(7)], seed=seed)
    session.load_robots("r.json", robots.read_bytes())  # an upload (a demo start loads the same way)
    assert session.mode == "run" and session.y_up == expected


def build_serve_args(robots, pattern, seed) -> argparse.Namespace:
    from apf_viz.cli import build_parser

    return build_parser().parse_args(
        ["serve", "--robots", str(robots), "--pattern", str(pattern), "--seed", str(seed)]
    )


def test_a_trace_larger_than_a_robots_file_is_replayed(write_json, tmp_path):
    robots = write_json("r.json", GOOD_ROBOTS)
    pattern = write_json("p.json", GOOD_PATTERN)
    trace = tmp_path / "t.jsonl"
    run = run_cli("run", "--robots", str(robots), "--pattern", str(pattern), "--trace", str(trace))
    assert run.returncode == 0, run.stderr
    big = tmp_path / "big.jsonl"  # over the 5 MB of a robots file: blank lines are allowed in a trace
    big.write_text(trace.read_text() + "\n" * 6_000_000)
    proc = run_cli("replay", "--trace", str(big))
    assert proc.returncode == 0, proc.stderr
    cut = tmp_path / "cut.jsonl"
    cut.write_text("\n".join(trace.read_text().splitlines()[:20]) + "\n")
    partial = run_cli("replay", "--trace", str(cut))
    assert partial.returncode == 1 and "the trace ends after 19 events, before the run does" in partial.stderr


def test_check_refuses_an_unsolvable_start_as_run_does(write_json):
    robots = write_json("r.json", {"robots": [[0, 0], [0, 3], [2, 1], [2, 2]]})
    pattern = write_json("p.json", {"points": [[0, 0], [1, 0], [2, 0], [3, 0]]})
    proc = run_cli("check", "--robots", str(robots), "--pattern", str(pattern))
    assert proc.returncode == 3 and "Theorem 1" in proc.stderr and proc.stderr.count("\n") == 1


def test_a_file_that_is_not_an_object_is_named_plainly(write_json):
    robots = write_json("r.json", [[0, 0], [1, 0]])
    pattern = write_json("p.json", GOOD_PATTERN)
    proc = run_cli("run", "--robots", str(robots), "--pattern", str(pattern))
    assert (
        proc.returncode == 2 and "expected a JSON object" in proc.stderr and "RobotsFile" not in proc.stderr
    )


def test_an_abbreviated_option_is_an_error_not_a_guess(write_json):
    robots, pattern = write_json("r.json", GOOD_ROBOTS), write_json("p.json", GOOD_PATTERN)
    out = run_cli("run", "--robot", str(robots), "--pattern", str(pattern))
    assert out.returncode == 2 and "required: --robots" in out.stderr


def test_sweep_names_the_valid_schedulers_and_semantics(tmp_path):
    out = run_cli(
        "sweep", "--ks", "3", "--seeds", "1", "--schedulers", "asynch", "--out", str(tmp_path / "r.csv")
    )
    assert out.returncode == 2 and "unknown scheduler 'asynch' (choose from fsync, ssync, async" in out.stderr
    out = run_cli("sweep", "--ks", "3", "--light-semantics", "lc", "--out", str(tmp_path / "r.csv"))
    assert out.returncode == 2 and "choose from compute, lc-atomic" in out.stderr


# ---------------------------------------------------------------- small words a newcomer reads
def test_progress_into_a_log_is_plain_lines_without_terminal_codes(tmp_path):
    """A sweep's or the lab's progress sent to a file: whole lines, no carriage returns or escapes, the
    last one always, the others at most every PLAIN_EVERY_S."""
    code = (
        "from apf_viz.progress import show_progress\n"
        "for i in range(50): show_progress(f'step {i}', last=False)\n"
        "show_progress('done', last=True)\n"
    )
    log = tmp_path / "log.txt"
    with log.open("w") as f:
        subprocess.run([sys.executable, "-c", code], stderr=f, check=True)
    text = log.read_text()
    assert "\r" not in text and "\x1b" not in text
    assert text.splitlines() == ["step 0", "done"]


def test_a_command_missing_two_extras_names_both_in_one_sentence(capsys):
    from apf_viz.cli.common import need_extra

    with pytest.raises(SystemExit) as stop:
        need_extra("sweep", ["no_such_module_a", "no_such_module_b"])
    assert stop.value.code == 2
    said = capsys.readouterr().err
    assert "(no_such_module_a and no_such_module_b are not installed)" in said


def test_one_more_problem_is_one_problem(tmp_path):
    bad = tmp_path / "r.json"
    bad.write_text('{"robots": [[0, "a"], [1, "b"]]}')
    proc = subprocess.run(
        [sys.executable, "-m", "apf_viz.cli", "run", "--robots", str(bad), "--pattern", str(bad)],
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 2 and "(and 1 more problem)" in proc.stderr, proc.stderr


def test_a_shape_pattern_is_named_after_what_made_it(tmp_path, capsys):
    assert main(["pattern", "--shape", "ring", "--size", "3"]) == 0
    assert json.loads(capsys.readouterr().out)["name"] == "ring of size 3"


def test_replay_says_every_event_matched(capsys):
    root = Path(__file__).resolve().parent
    assert main(["replay", "--trace", str(root / "gap_traces" / "E2.jsonl")]) == 1  # a collision
    out = capsys.readouterr().out
    assert out.startswith("replayed: all 67 events of ") and "match the engine's, one by one" in out


def test_ctrl_c_is_one_line_and_exit_130_wherever_it_comes(monkeypatch, capsys):
    import apf_viz.cli.replay as replay_command

    def interrupted(args):
        raise KeyboardInterrupt

    monkeypatch.setattr(replay_command, "run", interrupted)
    assert main(["replay", "--trace", "whatever.jsonl"]) == 130
    assert capsys.readouterr().err == "apf-viz: interrupted\n"


# ---------------------------------------------------------------- names, not paths, for what ships
def test_a_shipped_start_and_pattern_by_name_and_a_file_of_that_name_wins(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["run", "--robots", "sym-call-7", "--pattern", "cup-7"]) == 0
    said = capsys.readouterr()
    assert said.out.startswith("formed:")
    assert "--robots sym-call-7: the shipped robots file" in said.err and "starts/sym-call-7.json" in said.err
    # A file of that name in the working directory is the one used (and nothing is said).
    (tmp_path / "cup-7").write_text(json.dumps({"name": "mine", "points": [[0, 0]]}))
    with pytest.raises(SystemExit) as stop:
        main(["run", "--robots", "sym-call-7", "--pattern", "cup-7"])
    err = capsys.readouterr().err
    assert stop.value.code == 2 and "shipped pattern" not in err
    assert "cup-7: the pattern has 1 point but there are 7 robots" in err


def test_a_demo_scenario_by_a_word_of_its_title():
    from apf_viz.demos import find_scenario

    assert find_scenario("heart") == "Heart from 10 robots"
    assert find_scenario("lockstep") == "The L2 lockstep counterexample"
    assert find_scenario("Unsolvable box") == "Unsolvable box"
    with pytest.raises(ValueError, match="names several"):
        find_scenario("the")
    with pytest.raises(ValueError, match="names none"):
        find_scenario("zeppelin")


def test_demos_lists_what_ships_and_docs_prints_a_page(capsys):
    assert main(["demos"]) == 0
    out = capsys.readouterr().out
    assert "algorithm-in-12-stops — The algorithm in 12 stops, 12 stops" in out and "sym-call-7" in out
    assert main(["docs", "cli"]) == 0
    assert capsys.readouterr().out.startswith("# The command line")
    with pytest.raises(SystemExit) as stop:
        main(["docs", "nope"])
    assert stop.value.code == 2 and "no page 'nope' in the manual" in capsys.readouterr().err
