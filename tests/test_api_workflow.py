"""The research workflow from Python, each call against its command-line twin on generated starts: the
exact worst (``check(worst=…)`` / ``check --worst``), a goal-directed search (``want=`` / ``--want``), a
run that follows a schedule (``run(schedule=…)`` / ``run --schedule``) and a run's own schedule, the
searched adversary (``adversary`` / ``apf-viz adversary``), a lecture's check, a sweep's plots; every bad
argument a one-line InputError; progress shown by default and silenced by ``progress=False``; a shown run
and an unguarded sweep say nothing but what they must."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

import apf_viz
from apf_viz.api import progress_bars
from apf_viz.cli import main
from apf_viz.core.adversarial_starts import FAMILIES, generate
from apf_viz.core.formats import InputError
from tests.test_api import _cli_json

ROOT = Path(__file__).resolve().parent.parent
SMALL = [(family, seed) for family in sorted(FAMILIES) for seed in range(2)]  # 10 starts of k = 3


def _files(tmp_path: Path, family: str, seed: int, k: int = 3) -> tuple[Path, Path]:
    case = generate(family, seed, k=k, far=12)
    robots, pattern = tmp_path / "r.json", tmp_path / "p.json"
    robots.write_text(json.dumps({"robots": case.robots, "y_up": case.y_up}))
    pattern.write_text(json.dumps({"points": case.pattern}))
    return robots, pattern


@pytest.mark.parametrize(("family", "seed"), SMALL)
@pytest.mark.parametrize("measure", ["moves", "events"])
def test_the_exact_worst_is_the_command_lines_and_its_schedule_replays_to_it(
    tmp_path, capsys, family, seed, measure
):
    robots, pattern = _files(tmp_path, family, seed)
    out = tmp_path / "worst.schedule"
    cli = _cli_json(
        capsys, "check", "--robots", str(robots), "--pattern", str(pattern), "--worst", measure,
        "--json", "--schedule-out", str(out),
    )  # fmt: skip
    w = apf_viz.check(robots, pattern, worst=measure, progress=False)
    assert (w.verdict, w.value, w.k, w.D, w.states, list(w.y_up)) == (
        cli["verdict"], cli["worst"], cli["k"], cli["D"], cli["states"], cli["y_up"]
    )  # fmt: skip
    if w.verdict != "worst":
        return
    assert w.schedule == out.read_text()
    replayed = w.replay()
    assert (replayed.moves if measure == "moves" else replayed.events) == w.value
    assert replayed.outcome == "formed" and w.per_kD == pytest.approx(cli["per_kD"], abs=1e-4)
    mine = tmp_path / "mine.schedule"
    w.save_schedule(mine)
    assert mine.read_text() == w.schedule
    assert "schedule=" not in repr(w)  # the repr is one line, not the schedule


def test_want_finds_the_deadlock_a_person_reaches_by_hand(tmp_path, capsys):
    robots = {"robots": [[0, 0], [0, 1], [0, 2], [0, 4]], "y_up": [True, False, True, True]}
    (tmp_path / "r.json").write_text(json.dumps(robots))
    (tmp_path / "p.json").write_text(json.dumps({"points": [[0, 1], [1, 1], [2, 1], [1, 0]]}))
    args = ("--robots", str(tmp_path / "r.json"), "--pattern", str(tmp_path / "p.json"))
    literal = "apf-opaque-grid-literal"
    cli = _cli_json(capsys, "check", *args, "--algorithm", literal, "--want", "deadlock", "--json")
    v = apf_viz.check(
        tmp_path / "r.json", tmp_path / "p.json", algorithm=literal, want="deadlock", progress=False
    )
    assert (v.verdict, v.states, len(v.schedule)) == (cli["verdict"], cli["states"], cli["schedule_length"])
    assert v.verdict == "deadlock" and v.failed and v.replay().outcome == "stuck"


@pytest.mark.parametrize(("family", "seed"), SMALL[::2])
def test_a_run_that_follows_a_schedule_is_run_schedules_and_a_runs_schedule_replays_it(
    tmp_path, capsys, family, seed
):
    robots, pattern = _files(tmp_path, family, seed, k=4)
    for scheduler in ("async", "ssync", "fsync"):
        first = apf_viz.run(robots, pattern, scheduler=scheduler, seed=seed)
        first.save_schedule(tmp_path / "s.schedule")
        cli = _cli_json(
            capsys, "run", "--robots", str(robots), "--pattern", str(pattern),
            "--schedule", str(tmp_path / "s.schedule"), "--json",
        )  # fmt: skip
        again = apf_viz.run(robots, pattern, schedule=tmp_path / "s.schedule")
        assert again.as_dict() == cli
        assert (again.final, again.moves, again.events, again.outcome) == (
            first.final, first.moves, first.events, first.outcome
        )  # fmt: skip
        assert again.scheduler == "schedule"
    cut = "\n".join(first.schedule().splitlines()[:7]) + "\n"  # the header and six steps
    (tmp_path / "cut.schedule").write_text(cut)
    assert apf_viz.run(robots, pattern, schedule=tmp_path / "cut.schedule").outcome == "schedule-end"
    goes_on = apf_viz.run(robots, pattern, schedule=tmp_path / "cut.schedule", then="async")
    assert goes_on.outcome == "formed"
    with pytest.raises(InputError, match="then='async'"):
        apf_viz.run(robots, pattern, schedule=tmp_path / "cut.schedule", scheduler="async")


@pytest.mark.parametrize(("family", "seed"), [("symmetric-axis", 0), ("on-column", 1)])
def test_the_searched_adversary_is_the_command_lines_for_the_same_seed(tmp_path, capsys, family, seed):
    robots, pattern = _files(tmp_path, family, seed)
    out = tmp_path / "best.schedule"
    cli = _cli_json(
        capsys, "adversary", "--robots", str(robots), "--pattern", str(pattern), "--budget", "12",
        "--seed", "3", "--json", "--schedule-out", str(out),
    )  # fmt: skip
    f = apf_viz.adversary(robots, pattern, budget=12, seed=3, progress=False)
    assert (f.count, f.built_ins, f.exact, f.evaluations, f.built_in_runs, f.how) == (
        cli["found"], cli["built_ins"], cli["exact"], cli["evaluations"], cli["built_in_runs"], cli["how"]
    )  # fmt: skip
    assert f.schedule == out.read_text() and f.beats == cli["beats"]
    assert f.replay().moves == f.count


def test_a_lecture_checked_from_python_is_the_commands_check(capsys):
    capsys.readouterr()
    code = main(["lecture", "check", "what-a-robot-cannot-see"])
    lines = capsys.readouterr().out.splitlines()
    checked = apf_viz.lecture_check("what-a-robot-cannot-see")
    assert code == 0 and checked.passed
    stops = [line for line in lines if line.startswith(("  ok ", "  NOT "))]
    assert len(stops) == len(checked.stops) == 6
    for line, stop in zip(stops, checked.stops, strict=True):
        assert f"stop {stop.number}: {stop.title} (to {stop.until}; event {stop.event}" in line
    assert "6 of 6 stops hold" in repr(checked)


def test_plot_draws_the_commands_figures_from_a_sweeps_table(tmp_path, capsys):
    table = apf_viz.sweep(ks=[4], seeds=range(2), workers=1, progress=False)
    written = apf_viz.plot(table, tmp_path / "mine")
    table.to_csv(tmp_path / "t.csv", index=False)
    main(["plot", str(tmp_path / "t.csv"), "--out", str(tmp_path / "cli")])
    theirs = sorted(p.name for p in (tmp_path / "cli").iterdir())
    assert sorted(p.name for p in written) == theirs and theirs
    assert sorted(p.name for p in apf_viz.plot(tmp_path / "t.csv", tmp_path / "again")) == theirs
    with pytest.raises(InputError, match="DataFrame"):
        apf_viz.plot(42)


def test_every_bad_argument_is_the_documented_one_line_error(tmp_path):
    r = apf_viz.run("sym-call-7", "cup-7", seed=3)
    (tmp_path / "folder").mkdir()
    bad = {
        "run(None)": lambda: apf_viz.run(None, "cup-7"),  # type: ignore[arg-type]
        "run(bytes)": lambda: apf_viz.run(b"robots", "cup-7"),  # type: ignore[arg-type]
        "run(int)": lambda: apf_viz.run(3, "cup-7"),  # type: ignore[arg-type]
        "a point a string": lambda: apf_viz.run(["ab"], "cup-7"),  # type: ignore[list-item]
        "positions_at(1.5)": lambda: r.positions_at(1.5),  # type: ignore[arg-type]
        "positions_at(None)": lambda: r.positions_at(None),  # type: ignore[arg-type]
        "positions_at('3')": lambda: r.positions_at("3"),  # type: ignore[arg-type]
        "figure(select=-1)": lambda: r.figure(select=-1),
        "figure(select=True)": lambda: r.figure(select=True),
        "figure(fmt='pdf')": lambda: r.figure(fmt="pdf"),
        "figure(event=10**6)": lambda: r.figure(10**6),
        "save_trace(a folder)": lambda: r.save_trace(tmp_path / "folder"),
        "save_trace(a missing folder)": lambda: r.save_trace(tmp_path / "no" / "t.jsonl"),
        "save_schedule(a folder)": lambda: r.save_schedule(tmp_path / "folder"),
        "algorithm typo": lambda: apf_viz.run("sym-call-7", "cup-7", algorithm="apf-opaque-gird"),
        "algorithm not a name": lambda: apf_viz.run("sym-call-7", "cup-7", algorithm=3),  # type: ignore[arg-type]
        "max_events=0": lambda: apf_viz.run("sym-call-7", "cup-7", max_events=0),
        "max_moves=2.5": lambda: apf_viz.run("sym-call-7", "cup-7", max_moves=2.5),  # type: ignore[arg-type]
        "show(height=markup)": lambda: r.show(height='1"><script>'),  # type: ignore[arg-type]
        "then without a schedule": lambda: apf_viz.run("sym-call-7", "cup-7", then="async"),
        "schedule missing": lambda: apf_viz.run("sym-call-7", "cup-7", schedule=tmp_path / "none"),
        "sweep(ks=4)": lambda: apf_viz.sweep(ks=4),  # type: ignore[arg-type]
        "sweep(seeds='3')": lambda: apf_viz.sweep(ks=[4], seeds="3"),  # type: ignore[arg-type]
        "check(worst='time')": lambda: apf_viz.check("sym-call-7", "cup-7", worst="time"),  # type: ignore[call-overload]
        "check(want='crash')": lambda: apf_viz.check("sym-call-7", "cup-7", want="crash"),  # type: ignore[arg-type]
        "check(worst and want)": lambda: apf_viz.check(
            "one-on-L1-3", "corner-3", worst="moves", want="collision"
        ),  # type: ignore[call-overload]
        "check(max_states=0)": lambda: apf_viz.check("one-on-L1-3", "corner-3", max_states=0),
        "check(algorithm typo)": lambda: apf_viz.check("one-on-L1-3", "corner-3", algorithm="nope"),
        "adversary(budget=0)": lambda: apf_viz.adversary("one-on-L1-3", "corner-3", budget=0),
        "adversary(maximize='time')": lambda: apf_viz.adversary("one-on-L1-3", "corner-3", maximize="time"),
        "adversary(width=-1)": lambda: apf_viz.adversary("one-on-L1-3", "corner-3", width=-1),
        "lecture_check(3)": lambda: apf_viz.lecture_check(3),  # type: ignore[arg-type]
        "lecture_check(missing)": lambda: apf_viz.lecture_check("no-such-lecture"),
    }
    for what, call in bad.items():
        with pytest.raises(InputError) as caught:
            call()
        message = str(caught.value)
        assert "\n" not in message and message, what


def test_progress_is_shown_by_default_and_silenced_by_progress_false(monkeypatch, capsys):
    """A search longer than the quiet spell shows tqdm's bar on stderr; ``progress=False`` nothing; and
    without tqdm, the command line's own progress line."""
    monkeypatch.setattr(progress_bars, "QUIET_FOR_S", 0.0)
    args = ([(0, 0), (0, 1), (0, 2), (0, 4)], [(0, 1), (1, 1), (2, 1), (1, 0)])
    apf_viz.check(*args, algorithm="apf-opaque-grid-literal", progress=True)
    shown = capsys.readouterr()
    assert "apf-viz check" in shown.err and "states" in shown.err and shown.out == ""
    apf_viz.check(*args, algorithm="apf-opaque-grid-literal", progress=False)
    assert capsys.readouterr().err == ""
    monkeypatch.setattr(progress_bars.importlib.util, "find_spec", lambda name: None)
    bar = progress_bars.ProgressBar("apf-viz hunt", 10, "starts")
    bar.to(3, "0 failing")
    bar.close()
    err = capsys.readouterr().err
    assert "apf-viz hunt: 3/10 starts; 0 failing" in err and "apf-viz hunt: done" in err


@pytest.mark.slow
def test_a_run_shown_writes_nothing_but_its_page(tmp_path):
    script = (
        "import apf_viz\nshown = apf_viz.run('sym-call-7', 'cup-7', seed=3).show()\n"
        "assert '<iframe' in shown._repr_html_()\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, timeout=300, cwd=tmp_path
    )
    assert done.returncode == 0, done.stderr
    assert (done.stdout, done.stderr) == ("", "")


@pytest.mark.slow
def test_a_sweep_called_where_its_workers_cannot_import_the_caller_says_so_in_one_line(tmp_path):
    """A script without the ``__main__`` guard, and one read from standard input: the caller's one
    InputError, no worker's multiprocessing traceback; with the guard, the table."""
    call = "apf_viz.sweep(ks=[4], seeds=range(1), workers=1, progress=False)"
    script = tmp_path / "unguarded.py"
    script.write_text(f"import apf_viz\n{call}\n")
    done = subprocess.run(
        [sys.executable, str(script)], capture_output=True, text=True, timeout=300, cwd=tmp_path
    )
    assert done.returncode == 1
    assert 'under if __name__ == "__main__"' in done.stderr and "spawn" not in done.stderr
    assert done.stderr.count("Traceback") == 1  # the caller's own, ending in the one line
    piped = subprocess.run(
        [sys.executable, "-"],
        input=script.read_text(),
        capture_output=True,
        text=True,
        timeout=300,
        cwd=tmp_path,
    )
    assert (
        piped.returncode == 1 and "save the script as a file" in piped.stderr and "spawn" not in piped.stderr
    )
    guarded = tmp_path / "guarded.py"
    guarded.write_text(f"import apf_viz\nif __name__ == '__main__':\n    print(len({call}))\n")
    done = subprocess.run(
        [sys.executable, str(guarded)], capture_output=True, text=True, timeout=300, cwd=tmp_path
    )
    assert done.returncode == 0 and done.stdout.strip() == "1", done.stderr


def test_the_adversarys_notebook_runs_top_to_bottom(tmp_path):
    """docs/notebooks/the-adversary.py, as a kernel runs it: the exact worst beats the built-in
    schedulers, the search finds it, the worst schedule is shown and written, the hunt verifies."""
    notebook = ROOT / "docs" / "notebooks" / "the-adversary.py"
    done = subprocess.run(
        [sys.executable, "-c", f"import runpy; runpy.run_path({str(notebook)!r}, run_name='notebook')"],
        cwd=tmp_path, capture_output=True, text=True, env={**os.environ, "MPLBACKEND": "Agg"}, timeout=600,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-3000:]
    assert "the built-in schedulers' most: 59 moves; the search: 69; exact: 69" in done.stdout
    assert (tmp_path / "worst.schedule").read_text().startswith('{"format": "apf-viz-schedule"')


@pytest.mark.parametrize("fmt", ["svg", "tikz", "png"])
def test_a_runs_figure_is_the_commands_in_every_format(tmp_path, fmt):
    """``Run.figure(event, fmt, select, caption=True)`` is ``apf-viz figure … --caption`` byte for byte."""
    out = tmp_path / f"cli.{fmt}"
    main(
        ["figure", "--robots", "sym-call-7", "--pattern", "cup-7", "--seed", "3", "--event", "10",
         "--select", "2", "--caption", "--format", fmt, "--out", str(out)]
    )  # fmt: skip
    mine = apf_viz.run("sym-call-7", "cup-7", seed=3).figure(10, fmt=fmt, select=2, caption=True)
    assert (mine if isinstance(mine, bytes) else mine.encode()) == out.read_bytes()
