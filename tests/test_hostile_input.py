"""Hostile and careless input to the newer commands: refused in one line (exit 2), nothing lost, memory
bounded. Each test names the finding it guards (issue "A newcomer's first hour", items 1-11)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import threading
import tracemalloc
from pathlib import Path

import pytest

from apf_viz.core import files, formats, schedule
from apf_viz.core.formats import InputError, load_pattern, load_robots, load_trace
from apf_viz.core.grid import COORD_LIMIT
from apf_viz.core.schedule import load_schedule, parse_schedule_lines
from apf_viz.demos import DEMO_PATTERN, DEMO_START

ROOT = Path(__file__).resolve().parent.parent
CUP, CALL = ROOT / "demo_patterns" / "cup-7.json", ROOT / "demo_patterns" / "starts" / "sym-call-7.json"


def run_cli(*args: str, cwd: Path | None = None, env: dict | None = None) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "apf_viz.cli", *args], capture_output=True, text=True, cwd=cwd, env=env
    )


def one_line_exit_2(out: subprocess.CompletedProcess, *needles: str) -> None:
    assert out.returncode == 2, (out.returncode, out.stderr)
    assert out.stderr.count("\n") == 1 and "Traceback" not in out.stderr, out.stderr
    for needle in needles:
        assert needle in out.stderr, out.stderr


# ------------------------------------------------------------------------- 1. device files, read to a limit
@pytest.mark.parametrize(
    "load, limit_of",
    [
        (load_robots, None),
        (load_pattern, None),
        (load_trace, (formats, "MAX_TRACE_BYTES")),
        (load_schedule, (schedule, "MAX_SCHEDULE_BYTES")),
    ],
    ids=["robots", "pattern", "trace", "schedule"],
)
def test_a_file_is_read_only_up_to_the_limit(tmp_path, monkeypatch, load, limit_of):
    if limit_of is not None:
        monkeypatch.setattr(*limit_of, 1_000_000)  # the real 1 GB would only make the test slow
    big = tmp_path / "big"
    big.write_bytes(b"{" + b" " * 5_000_001)
    with pytest.raises(InputError, match=r"big: file is too large \(more than [\d,]+ bytes\)"):
        load(big)


@pytest.mark.parametrize("load", [load_robots, load_pattern, load_trace, load_schedule])
def test_a_fifo_is_refused_by_its_type_with_or_without_a_writer(tmp_path, load):
    """A FIFO is never read: with no writer, open() would wait for ever; with one, it may never end."""
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    with pytest.raises(InputError, match=r"fifo: is a FIFO, not a regular file"):
        load(fifo)

    def feed() -> None:
        try:
            with open(fifo, "wb") as f:
                f.write(b"{}" * 1000)
        except BrokenPipeError:
            pass

    writer = threading.Thread(target=feed, daemon=True)
    writer.start()
    with pytest.raises(InputError, match=r"fifo: is a FIFO"):
        load(fifo)
    os.close(os.open(fifo, os.O_RDONLY | os.O_NONBLOCK))  # let the writer go, whatever the load did
    writer.join(timeout=10)


@pytest.mark.skipif(not Path("/dev/zero").exists(), reason="no /dev/zero here")
def test_run_with_dev_zero_as_robots_is_one_line():
    one_line_exit_2(
        run_cli("run", "--robots", "/dev/zero", "--pattern", str(CUP)), "/dev/zero", "is a character device"
    )


# ------------------------------------------------------------------------- 2, 3. tables that are not ours
def test_sweep_out_refuses_a_file_that_is_not_its_results_table_and_keeps_it(tmp_path):
    notes = tmp_path / "notes.csv"
    notes.write_text("important notes\n")
    other = tmp_path / "other.csv"
    other.write_text("a,b\n1,2\n")
    for path, needle in ((notes, "missing columns k, D, seed"), (other, "columns it does not write: a, b")):
        before = path.read_bytes()
        out = run_cli("sweep", "--workers", "1", "--ks", "3", "--seeds", "1", "--out", str(path))
        one_line_exit_2(out, str(path), needle)
        assert path.read_bytes() == before


def test_a_results_table_without_outcome_and_a_parquet_of_other_columns_are_one_line(tmp_path):
    import pyarrow as pa
    import pyarrow.parquet as pq

    from apf_viz.sweeps import COLUMNS

    partial = tmp_path / "partial.csv"
    partial.write_text(",".join(c for c in COLUMNS if c != "outcome") + "\n")
    one_line_exit_2(
        run_cli("sweep", "--workers", "1", "--ks", "3", "--seeds", "1", "--out", str(partial)),
        "missing columns outcome",
    )
    table = tmp_path / "other.parquet"
    pq.write_table(pa.table({"a": [1], "b": [2]}), table)
    one_line_exit_2(
        run_cli("sweep", "--workers", "1", "--ks", "3", "--seeds", "1", "--out", str(table)),
        "missing columns k",
    )
    one_line_exit_2(run_cli("plot", str(partial), "--out", str(tmp_path / "d")), "missing columns outcome")
    one_line_exit_2(run_cli("plot", str(table), "--out", str(tmp_path / "d")), "missing columns")


# ------------------------------------------------------------------------- 4. huge ranges, counted first
@pytest.mark.parametrize(
    "flag, value, needle",
    [
        ("--ks", "1-10000000000", "more than the 100,000"),
        ("--seeds", "0-10000000000", "more than the 100,000"),
        ("--ks", "100001", "at most 100,000 robots"),
        ("--ks", "0", "at least one robot"),
    ],
)
def test_sweep_refuses_huge_grids_before_building_them(tmp_path, flag, value, needle):
    args = {"--ks": "3", "--seeds": "1", flag: value}
    argv = [x for pair in args.items() for x in pair]
    out = run_cli("sweep", *argv, "--workers", "1", "--out", str(tmp_path / "r.csv"))
    one_line_exit_2(out, needle)
    assert not (tmp_path / "r.csv").exists()


def test_a_sweep_of_more_runs_than_the_maximum_is_refused(tmp_path):
    out = run_cli(
        "sweep", "--ks", "1-1000", "--seeds", "1-2000", "--workers", "1", "--out", str(tmp_path / "r.csv")
    )
    one_line_exit_2(out, "2,000,000 runs", "split it")


# ------------------------------------------------------------------------- 5. random boxes past 2^63 cells
@pytest.mark.parametrize("command", ["random-robots", "random-pattern"])
def test_random_points_in_the_largest_box_the_limits_allow(command):
    side = str(COORD_LIMIT + 1)
    out = run_cli(command, "--count", "3", "--width", side, "--height", side, "--seed", "4")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    points = data.get("robots") or data.get("points")
    assert len({tuple(p) for p in points}) == 3
    assert all(0 <= c <= int(side) - 1 for p in points for c in p)


# ------------------------------------------------------------------------- 6. schedules held compactly
def test_a_schedule_line_costs_tens_of_bytes_not_hundreds():
    n = 20_000  # enough lines that the fixed costs vanish; tracemalloc slows every allocation

    def lines():
        yield 1, json.dumps({"format": "apf-viz-schedule", "version": 2, "robots": 10})
        for i in range(n):
            yield i + 2, json.dumps({"robot": i % 10, "phase": ("look", "compute", "move")[i % 3]})

    tracemalloc.start()
    try:
        parsed = parse_schedule_lines(lines())
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert len(parsed) == n
    assert peak / n < 60, f"{peak / n:.0f} bytes per line"  # pydantic objects in a list: about 900


# ------------------------------------------------------------------------- 7, 8. output paths and clusters
@pytest.mark.slow
def test_an_unreachable_cluster_is_named_with_its_reason(tmp_path):
    out = run_cli(
        "sweep",
        "--ks",
        "3",
        "--seeds",
        "1",
        "--cluster",
        "tcp://127.0.0.1:9",
        "--out",
        str(tmp_path / "r.csv"),
    )
    one_line_exit_2(out, "--cluster tcp://127.0.0.1:9: cannot reach a Dask scheduler there (")
    assert "None" not in out.stderr


def test_schedule_out_a_directory_is_refused_before_reading_the_trace(tmp_path):
    trace = ROOT / "tests" / "gap_traces" / "L2.jsonl"
    out = run_cli("schedule", "--from-trace", str(trace), "--out", str(tmp_path))
    one_line_exit_2(out, f"{tmp_path}: is a directory")
    assert ".tmp" not in out.stderr


SCHEDULE_HEADER = {"format": "apf-viz-schedule", "version": 2, "robots": 10, "y_up": [True] * 10}


def run_schedule(tmp_path: Path, lines: list[dict]):
    """The Demo's run following a schedule of these lines: the schedule's path, the command's result and
    the events of the trace it kept."""
    sched = tmp_path / "s.jsonl"
    sched.write_text("\n".join(json.dumps(x) for x in [SCHEDULE_HEADER, *lines]) + "\n")
    trace = tmp_path / "t.jsonl"
    out = run_cli(
        "run", "--robots", str(DEMO_START), "--pattern", str(DEMO_PATTERN), "--schedule", str(sched),
        "--trace", str(trace),
    )  # fmt: skip
    return sched, out, load_trace(trace)[1] if trace.exists() else []


# ------------------------------------------------------------------------- 9. negative robots
@pytest.mark.parametrize("line", [{"round": [-1]}, {"round": [0, -1]}, {"robot": -1, "phase": "look"}])
def test_a_negative_robot_is_refused_with_its_line_and_the_run_so_far_kept(tmp_path, line):
    body = [{"robot": 0, "phase": "look"}, {"robot": 0, "phase": "compute"}, {"robot": 0, "phase": "move"}]
    sched, out, events = run_schedule(tmp_path, [*body, line])
    one_line_exit_2(out, f"{sched}:5: robot -1 does not exist (10 robots)")
    assert [(e.robot, e.phase) for e in events] == [(0, "look"), (0, "compute"), (0, "move")]


# ------------------------------------------------------------------------- 10. the sweep extra missing
@pytest.mark.parametrize("command, blocked", [("sweep", "dask"), ("plot", "matplotlib")])
def test_a_command_without_its_extra_says_which_to_install(tmp_path, command, blocked):
    argv = ["sweep", "--ks", "3", "--seeds", "1", "--out", str(tmp_path / "r.csv")]
    if command == "plot":
        (tmp_path / "r.csv").write_text("k\n")
        argv = ["plot", str(tmp_path / "r.csv")]
    code = (
        f"import sys; sys.modules[{blocked!r}] = None; from apf_viz.cli import main; sys.exit(main({argv!r}))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    one_line_exit_2(out, f"apf-viz {command} needs the sweep extra ({blocked} is not installed)", "[sweep]")


# ------------------------------------------------------------------------- 11. a run past its time
def test_a_run_past_run_timeout_is_recorded_as_timeout_and_the_sweep_goes_on(tmp_path):
    from apf_viz.sweeps import grid, run_sweep

    starts = tmp_path / "starts"
    starts.mkdir()
    # A long walk: minutes without a limit under SSYNC, which is never fast-forwarded (a round is a choice).
    far = [[0, 0], [100_000, 3], [2, 100_000]]
    (starts / "far.robots.json").write_text(json.dumps({"robots": far, "y_up": [True, True, False]}))
    (starts / "far.pattern.json").write_text(json.dumps({"points": [[0, 0], [1, 0], [0, 2]]}))
    (starts / "near.robots.json").write_text(json.dumps({"robots": [[0, 0], [3, 0], [1, 2]]}))
    (starts / "near.pattern.json").write_text(json.dumps({"points": [[0, 0], [1, 0], [0, 2]]}))
    seen = []
    cells = grid([], [1], ["ssync"], ["apf-opaque-grid"], ["compute"], starts)
    rows = run_sweep(cells, tmp_path / "r.csv", workers=1, run_timeout=3.0, progress=seen.append)
    by_start = {r["start"]: r for r in rows}
    assert by_start["near"]["outcome"] == "formed"
    far_row = by_start["far"]
    assert far_row["outcome"] == "timeout" and far_row["moves"] > 0 and 3.0 <= far_row["wall_s"] < 60
    assert any("far seed 1 ssync" in p.slowest for p in seen), [p.slowest for p in seen]
    assert seen[-1].finished == seen[-1].total == 2


def test_the_eta_weighs_runs_by_their_size():
    from apf_viz.sweeps import Cell, cost

    small, large = Cell(10, 1, "async", "apf-opaque-grid", "compute"), Cell(100, 1, "async", "x", "compute")
    assert cost(large) > 20 * cost(small)


# ------------------------------------------------- output paths that are not regular files, and limits
# Issue "Claims that survive an adversary", item 3: each refused in one line with exit 2 (each fails on
# the code before it). Device nodes are made privately in tmp_path, never the system's.
def special_files(tmp_path: Path) -> list[tuple[Path, str]]:
    import socket
    import stat

    made = []
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    made.append((fifo, "a FIFO"))
    sock_path = tmp_path / "sock"
    sock = socket.socket(socket.AF_UNIX)
    sock.bind(str(sock_path))
    sock.close()
    made.append((sock_path, "a socket"))
    device = tmp_path / "null"
    try:  # a private copy of /dev/null's node (root, as CI runs; elsewhere the FIFO and socket remain)
        os.mknod(device, stat.S_IFCHR | 0o666, os.makedev(1, 3))
        made.append((device, "a character device"))
    except PermissionError:
        pass
    return made


def output_commands(out: Path) -> list[list[str]]:
    robots, pattern = str(ROOT / "demo_patterns" / "starts" / "sym-call-7.json"), str(CUP)
    run = ["run", "--robots", robots, "--pattern", pattern, "--max-events", "50"]
    return [
        [*run, "--trace", str(out)],
        [*run, "--schedule-out", str(out)],
        ["pattern", "--shape", "box", "--size", "2", "--out", str(out)],
        ["random-robots", "--count", "3", "--width", "4", "--height", "4", "--out", str(out)],
    ]


def test_an_output_path_that_is_a_device_fifo_or_socket_is_refused_and_left_as_it_is(tmp_path):
    for path, kind in special_files(tmp_path):
        before = os.lstat(path)
        for command in output_commands(path):
            out = run_cli(*command)
            one_line_exit_2(out, str(path), f"is {kind}, not a regular file")
            after = os.lstat(path)
            assert (after.st_mode, after.st_ino, after.st_rdev) == (
                before.st_mode,
                before.st_ino,
                before.st_rdev,
            )
        assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]  # no temporary file left


def test_the_atomic_rename_itself_refuses_a_special_file(tmp_path):
    """Every writer (tables, images, counterexamples) goes through replace_atomically."""
    for path, kind in special_files(tmp_path):
        with pytest.raises(InputError, match=f"is {kind}"):
            files.write_atomic(path, "text")
        with pytest.raises(InputError, match=f"is {kind}"):
            files.replace_atomically(path, lambda tmp: Path(tmp).write_text("x"))
    regular = tmp_path / "regular.txt"
    regular.write_text("old")
    link = tmp_path / "link.txt"
    link.symlink_to(regular)
    files.write_atomic(link, "new")  # a link to a regular file: written through, the link stays a link
    assert link.is_symlink() and regular.read_text() == "new"


def test_a_schedule_line_naming_a_robot_beyond_any_index_keeps_the_run_up_to_it(tmp_path):
    sched, out, events = run_schedule(
        tmp_path, [{"robot": 0, "phase": "look"}, {"robot": 10**23, "phase": "look"}]
    )
    one_line_exit_2(out, f"{sched}:3: robot {10**23} does not exist (10 robots)")
    assert [(e.robot, e.phase) for e in events] == [(0, "look")]
    sched, out, _ = run_schedule(tmp_path, [{"round": [0, 10**23]}])
    one_line_exit_2(out, "does not exist")


def test_lights_random_beyond_its_maximum_is_refused(tmp_path):
    from apf_viz.lights import MAX_RANDOM_RUNS

    out = run_cli("lights", "--out", str(tmp_path / "l.parquet"), "--random", str(10**12))
    one_line_exit_2(out, f"--random {10**12:,}", f"from 0 to {MAX_RANDOM_RUNS:,}")
    assert not (tmp_path / "l.parquet").exists()


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["--text", "   "], "no cells to draw"),
        (["--shape", "box", "--size", "0"], "--shape box --size 0"),
        (["--shape", "outline", "--size", "-2"], "--shape outline --size -2"),
        (["--shape", "row", "--size", "0"], "--shape row --size 0"),
    ],
)
def test_a_pattern_with_no_cells_or_a_size_below_one_is_refused(tmp_path, args, needle):
    out = run_cli("pattern", *args, "--out", str(tmp_path / "p.json"))
    one_line_exit_2(out, needle)
    assert not (tmp_path / "p.json").exists()


def test_ascii_art_of_millions_of_cells_is_refused_before_they_are_made(tmp_path):
    art = tmp_path / "big.txt"
    art.write_text(("#" * 999 + "\n") * 4900)  # 4.9 MB, under the file limit
    tracemalloc.start()
    try:
        with pytest.raises(Exception, match="4,895,100 '#' cells, more than 10,000"):
            from apf_viz.core import shapes

            shapes.ascii_art(art.read_text().splitlines())
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 60_000_000, peak  # the text and its lines; 4.9 million cells would be hundreds of MB
    one_line_exit_2(run_cli("pattern", "--ascii", str(art)), f"{art}: 4,895,100 '#' cells")


def test_serve_library_naming_a_file_is_refused(tmp_path):
    from apf_viz.workbench.library import PatternLibrary

    afile = tmp_path / "patterns.json"
    afile.write_text("{}")
    with pytest.raises(InputError, match="is a file, not a folder"):
        PatternLibrary(afile)
    out = run_cli("serve", "--library", str(afile), "--port", "0")
    one_line_exit_2(out, f"--library {afile}: is a file, not a folder")
    assert afile.read_text() == "{}"


@pytest.mark.parametrize("command", ["sweep", "lights"])
def test_workers_beyond_the_machine_and_an_in_process_cluster_are_refused(tmp_path, command):
    out = tmp_path / "x.parquet"
    one_line_exit_2(run_cli(command, "--out", str(out), "--workers", "100000"), "100,000 local worker")
    one_line_exit_2(run_cli(command, "--out", str(out), "--cluster", "inproc://x"),
                    "'inproc://x' is not a Dask scheduler's address")  # fmt: skip
    assert not out.exists()


@pytest.mark.parametrize("cap", range(3, 40))
def test_max_events_under_lc_atomic_is_never_passed(cap):
    from apf_viz.algorithms import get_algorithm
    from apf_viz.core.engine import Engine
    from apf_viz.core.run import advance
    from apf_viz.core.schedulers import make_scheduler

    for fast in (False, True):
        e = Engine([(1, 1), (2, -60)], [(2, 2), (0, 2)], get_algorithm("apf-opaque-grid"),
                   light_semantics="lc-atomic", max_events=cap, fast_forward=fast)  # fmt: skip
        advance(e, make_scheduler("async"), 1)
        assert e.outcome == "limit" and cap - 1 <= e.state.events <= cap, (cap, e.state.events)


@pytest.mark.parametrize("command", ["sweep", "lights"])
def test_a_cluster_address_of_a_protocol_not_installed_is_one_line_and_leaves_no_folder(tmp_path, command):
    """Before: a 40-line traceback (ucx:// needs a package Dask does not bring) and an empty traces folder."""
    args = ["--ks", "3", "--seeds", "1"] if command == "sweep" else ["--ks", "1-2", "--merges", "off=call"]
    args += ["--cluster", "ucx://x:1", "--out", "r.parquet", "--traces", "tr"]
    out = run_cli(command, *args, cwd=tmp_path)
    one_line_exit_2(out, "--cluster ucx://x:1: cannot reach a Dask scheduler there")
    assert list(tmp_path.iterdir()) == []


def test_a_cluster_address_where_a_peer_accepts_and_never_speaks_is_one_line(monkeypatch):
    """Before, sweep and lights waited for ever: Dask's own timeout does not cover a silent peer."""
    import socket

    from apf_viz.sweeps import driver

    monkeypatch.setattr(driver, "CONNECT_SECONDS", 2.0)
    with socket.socket() as silent:
        silent.bind(("127.0.0.1", 0))
        silent.listen(4)
        address = f"tcp://127.0.0.1:{silent.getsockname()[1]}"
        with pytest.raises(InputError, match="no Dask scheduler answered there within 2 s"):
            driver.dask_client(address, None)
