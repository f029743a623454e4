"""Files and CLI: every malformed input is one line naming the file and the problem, exit code 2."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from apf_viz.cli import main
from apf_viz.core.formats import InputError, load_trace, write_atomic
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
    assert set(out) == {"outcome", "final", "moves", "events", "cycles", "lights_used"}
    assert out["final"] == [[0, 0], [1, 0], [2, 0], [0, 2], [1, 2]]
    header, events = load_trace(trace)
    assert header.scheduler == "stale-first" and header.seed == 5 and len(events) == out["events"]
    assert main(["replay", "--trace", str(trace), "--json"]) == 0
    assert json.loads(capsys.readouterr().out) == out


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
