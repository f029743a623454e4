"""`apf-viz sweep` and `apf-viz plot` with a real Dask LocalCluster of 2 worker processes."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from apf_viz.sweeps import COLUMNS, KEY, grid, read_results, run_sweep

ROOT = Path(__file__).resolve().parent.parent


def run_cli(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "apf_viz.cli", *args], capture_output=True, text=True, cwd=cwd
    )


def keys(rows: list[dict]) -> list[tuple]:
    return [tuple(r[c] for c in KEY) for r in rows]


def test_a_tiny_sweep_gives_one_row_per_run_with_every_column(tmp_path):
    out = tmp_path / "results.parquet"
    cells = grid([3, 4], [1, 2], ["async"], ["apf-opaque-grid", "apf-opaque-grid-literal"], ["compute"])
    rows = run_sweep(cells, out, traces=tmp_path / "fails", workers=2)
    table = read_results(out)
    assert len(table) == len(rows) == 8 and sorted(keys(table)) == sorted(c.key() for c in cells)
    assert all(set(r) == set(COLUMNS) for r in table)
    default = [r for r in table if r["algorithm"] == "apf-opaque-grid"]
    assert all(r["outcome"] == "formed" and r["trace"] == "" for r in default)
    assert all(r["moves_per_kD"] == pytest.approx(r["moves"] / (r["k"] * r["D"])) for r in table)
    for r in table:  # a trace exactly for every run that did not form
        assert (r["trace"] != "") == (r["outcome"] != "formed")


def test_a_sweep_resumes_without_duplicates_and_keeps_what_was_done(tmp_path):
    out = tmp_path / "results.csv"
    first = run_sweep(grid([3], [1, 2], ["async"], ["apf-opaque-grid"], ["compute"]), out, workers=2)
    assert len(read_results(out)) == 2
    cells = grid([3, 4], [1, 2], ["async", "round-robin"], ["apf-opaque-grid"], ["compute"])
    rows = run_sweep(cells, out, workers=2)  # as if the first sweep had been interrupted after 2 runs
    assert len(rows) == len(cells) == 8 and len(set(keys(rows))) == 8
    kept = {tuple(r[c] for c in KEY): r["wall_s"] for r in read_results(out)}
    assert all(kept[tuple(r[c] for c in KEY)] == pytest.approx(r["wall_s"]) for r in first)  # not re-run


def test_a_run_that_kills_its_worker_is_recorded_as_error_and_the_sweep_goes_on(tmp_path, monkeypatch):
    # distributed's config loaded before the set below: an older dask (2024.1) restores a key the set
    # made by deleting it whole, with every default distributed put under it meanwhile
    import dask
    import dask.distributed

    from tests.sweep_helpers import crash_on_k4_seed2

    monkeypatch.setenv("PYTHONPATH", str(ROOT))  # the workers import tests.sweep_helpers
    out = tmp_path / "results.parquet"
    cells = grid([3, 4], [1, 2], ["async"], ["apf-opaque-grid"], ["compute"])
    # One task per single-threaded worker at a time (by default a worker also holds a queued task, which
    # dies with it), and Dask's retries kept: a run that happened to share a dying worker is run again,
    # while the crashing one dies on every retry and is recorded as an error.
    with dask.config.set({"distributed.scheduler.worker-saturation": 1.0}):
        rows = run_sweep(cells, out, workers=2, run=crash_on_k4_seed2)
    by_key = {(r["k"], r["seed"]): r for r in rows}
    assert by_key[(4, 2)]["outcome"] == "error" and "KilledWorker" in by_key[(4, 2)]["error"]
    assert [by_key[k]["outcome"] for k in [(3, 1), (3, 2), (4, 1)]] == ["formed"] * 3


def test_starts_from_a_folder_of_pairs(tmp_path):
    starts = tmp_path / "starts"
    starts.mkdir()
    demos = ROOT / "demo_patterns"
    (starts / "line.robots.json").write_text((demos / "starts" / "vertical-line-4.json").read_text())
    (starts / "line.pattern.json").write_text((demos / "tee-4.json").read_text())
    (starts / "call.robots.json").write_text((demos / "starts" / "sym-call-7.json").read_text())
    (starts / "call.pattern.json").write_text((demos / "cup-7.json").read_text())
    out = tmp_path / "r.parquet"
    rows = run_sweep(grid([], [1], ["async"], ["apf-opaque-grid"], ["compute"], starts), out, workers=2)
    assert sorted((r["start"], r["k"], r["outcome"]) for r in rows) == [
        ("call", 7, "formed"),
        ("line", 4, "formed"),
    ]


@pytest.mark.parametrize(
    "args, message",
    [
        (["--algorithms", "nope"], "--algorithms: unknown algorithm 'nope'"),
        (["--seeds", "5-1"], "--seeds '5-1': the range 5-1 runs backwards"),
        (["--out", "/proc/nope/r.parquet"], "/proc/nope/r.parquet"),
        (["--out", "r.txt"], "write .parquet or .csv"),
        (["--schedulers", "manual"], "unknown scheduler 'manual'"),
    ],
)
def test_bad_sweep_input_is_one_line_exit_2(tmp_path, args, message):
    base = {"--out": str(tmp_path / "r.parquet")}
    argv = ["sweep", "--ks", "3", "--seeds", "1"]
    for flag, value in zip(args[::2], args[1::2], strict=True):
        base[flag] = value
    for flag, value in base.items():
        argv += [flag, value]
    out = run_cli(*argv, cwd=tmp_path)
    assert out.returncode == 2 and message in out.stderr and out.stderr.count("\n") == 1, out.stderr


def test_the_cli_sweep_prints_a_summary_and_plot_writes_the_figures(tmp_path):
    out = tmp_path / "r.parquet"
    done = run_cli("sweep", "--ks", "3,4", "--seeds", "1-2", "--workers", "2", "--out", str(out))
    assert done.returncode == 0, done.stderr
    assert "| apf-opaque-grid | async | compute | 4 | 4 | none |" in done.stdout
    assert "4/4 runs" in done.stderr  # progress with an ETA on stderr
    again = run_cli("sweep", "--ks", "3,4", "--seeds", "1-2", "--workers", "2", "--out", str(out))
    assert again.returncode == 0 and len(read_results(out)) == 4  # nothing re-run, nothing duplicated
    plots = run_cli("plot", str(out), "--out", str(tmp_path / "plots"))
    assert plots.returncode == 0, plots.stderr
    for name in ("moves_vs_kD.png", "failure_rate.png", "events_per_move.png", "time_per_move.png"):
        png = tmp_path / "plots" / name
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 5_000
    json.dumps(read_results(out))  # plain values: a row is JSON-able


def test_a_generated_row_is_reproduced_by_the_documented_apf_viz_run_recipe(tmp_path):
    import math

    from apf_viz.sweeps import Cell, run_cell

    k, seed = 6, 3
    r = run_cell(Cell(k, seed, "stale-first", "apf-opaque-grid", "compute"))
    s = max(3, math.isqrt(3 * k) + 1)
    robots = run_cli(
        "random-robots", "--count", str(k), "--width", str(s), "--height", str(s), "--seed", str(2 * seed)
    )
    pattern = run_cli("random-pattern", "--count", str(k), "--width", str(s), "--height", str(s),
                      "--seed", str(2 * seed + 1))  # fmt: skip
    (tmp_path / "r.json").write_text(robots.stdout)
    (tmp_path / "p.json").write_text(pattern.stdout)
    out = run_cli("run", "--robots", str(tmp_path / "r.json"), "--pattern", str(tmp_path / "p.json"),
                  "--scheduler", "stale-first", "--seed", str(seed), "--json")  # fmt: skip
    data = json.loads(out.stdout)
    assert (data["outcome"], data["moves"], data["events"], data["D"]) == (
        r["outcome"],
        r["moves"],
        r["events"],
        r["D"],
    )


@pytest.mark.slow
def test_ctrl_c_keeps_a_valid_results_file_and_the_same_command_resumes_it(tmp_path):
    from tests.sweep_helpers import interrupt_when

    out = tmp_path / "r.csv"
    # Runs of seconds each (k = 100: about 2–3 s, k = 80 once took 4 s but the engine got faster), so that
    # Ctrl+C lands with most of the grid still to run: the first rows are written after 5 s.
    argv = [sys.executable, "-m", "apf_viz.cli", "sweep", "--ks", "60,80,100", "--seeds", "1-4",
            "--workers", "2", "--out", str(out)]  # fmt: skip
    # Ctrl+C as soon as the progress line counts a finished run (not when its row is on disk: rows are
    # written every few seconds, and on a loaded machine the first write came after the last run).
    code, err = interrupt_when(argv, tmp_path, rb"[1-9][0-9]*/12 runs")
    assert code == 130 and "interrupted; keeping the runs that finished" in err, err[-300:]
    kept = read_results(out)
    assert 1 <= len(kept) < 12 and len(set(keys(kept))) == len(kept)  # a valid, partial table
    again = run_cli(*argv[3:], cwd=tmp_path)
    assert again.returncode == 0, again.stderr
    rows = read_results(out)
    assert len(rows) == 12 and len(set(keys(rows))) == 12  # resumed: the rest run, nothing twice
    first = {tuple(r[c] for c in KEY): r["wall_s"] for r in kept}
    assert all(
        first[k] == pytest.approx(w)
        for k, w in ((tuple(r[c] for c in KEY), r["wall_s"]) for r in rows)
        if k in first
    )


def test_a_grid_of_no_robots_or_negative_seeds_is_bad_input(tmp_path):
    for args, message in (
        (["--ks", "0"], "--ks: a run needs at least one robot"),
        (["--seeds", "-3"], "--seeds:"),
    ):
        out = run_cli(
            "sweep", "--ks", "3", "--seeds", "1", *args, "--out", str(tmp_path / "r.csv"), cwd=tmp_path
        )
        assert out.returncode == 2 and message in out.stderr, out.stderr


def test_a_sweep_whose_progress_reader_goes_away_still_runs_to_the_end_and_keeps_its_rows(tmp_path):
    """`apf-viz sweep … 2>&1 | head -0`: the pipe its progress goes into closes at once. The sweep went
    down with the first progress line and wrote nothing; now the line is dropped and the runs kept."""
    out = tmp_path / "r.parquet"
    args = ["sweep", "--ks", "3", "--seeds", "1-2", "--workers", "2", "--out", str(out)]
    p = subprocess.Popen(
        [sys.executable, "-m", "apf_viz.cli", *args], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE
    )
    p.stderr.close()  # nobody reads the progress
    assert p.wait(timeout=300) == 0
    assert sorted((r["k"], r["seed"]) for r in read_results(out)) == [(3, 1), (3, 2)]


def test_the_searched_adversary_is_a_column_of_the_table_and_plot_draws_it_against_the_built_ins(tmp_path):
    """`--schedulers …,worst-found`: for each start the searched adversary's costliest schedule (moves)
    is a row beside the built-ins', never below their most there (it starts from their best over seeds
    0–19), and beyond it on the generated k = 5 start of seed 5 (exact worst 60, built-ins 44);
    `apf-viz plot` draws both per start in worst_vs_kD.png."""
    from apf_viz.charts import worst_against_built_ins

    out = tmp_path / "r.csv"
    done = run_cli("sweep", "--ks", "4,5", "--seeds", "5", "--schedulers", "async,fsync,worst-found",
                   "--workers", "2", "--out", str(out))  # fmt: skip
    assert done.returncode == 0, done.stderr
    table = read_results(out)
    searched = [r for r in table if r["scheduler"] == "worst-found"]
    built = [r for r in table if r["scheduler"] != "worst-found"]
    assert len(searched) == 2 and len(built) == 4 and all(r["outcome"] == "formed" for r in table)
    compared = worst_against_built_ins(searched, built)
    assert len(compared) == 2 and all(found >= most for _, found, most in compared)
    five = next(r for r in searched if r["k"] == 5)
    assert five["moves"] == 60 and five["moves"] > max(r["moves"] for r in built if r["k"] == 5)
    plots = run_cli("plot", str(out), "--out", str(tmp_path / "plots"))
    assert plots.returncode == 0, plots.stderr
    png = tmp_path / "plots" / "worst_vs_kD.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 5_000


def test_every_column_of_the_table_is_documented():
    """docs/SWEEPS.md's table of columns names every column a sweep writes (one row may name several)."""
    import re

    from apf_viz.sweeps.cells import COLUMNS

    text = (Path(__file__).resolve().parent.parent / "docs" / "SWEEPS.md").read_text()
    table = text.split("## The columns", 1)[1].split("\n## ", 1)[0]
    named = {
        name.strip() for row in re.findall(r"^\| ([^|]+) \|", table, flags=re.M) for name in row.split(",")
    }
    assert set(COLUMNS) - named == set()
