"""apf-viz from Python (apf_viz.run, sweep, check): the command line's numbers for the same inputs, on
generated starts of the adversarial families under every scheduler; docs/API.md's examples and the
notebook run as written, in an empty folder; a plug-in found in the current folder."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import pytest

import apf_viz
from apf_viz.cli import main
from apf_viz.core.adversarial_starts import FAMILIES, generate
from apf_viz.core.formats import InputError, load_trace
from apf_viz.core.schedulers import AUTOMATIC

ROOT = Path(__file__).resolve().parent.parent
CASES = [(family, seed) for family in sorted(FAMILIES) for seed in range(3)]


def _files(tmp_path: Path, case) -> tuple[Path, Path]:
    robots = tmp_path / "r.json"
    pattern = tmp_path / "p.json"
    robots.write_text(json.dumps({"robots": case.robots, "y_up": case.y_up}))
    pattern.write_text(json.dumps({"points": case.pattern}))
    return robots, pattern


def _cli_json(capsys, *argv: str) -> dict:
    capsys.readouterr()
    main(list(argv))
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize(("family", "case_seed"), CASES)
def test_run_has_the_command_lines_numbers_on_generated_starts_under_every_scheduler(
    tmp_path, capsys, family, case_seed
):
    """Every field of ``apf-viz run --json`` (outcome, final positions, moves, events, cycles, skipped,
    moves/(k·D), caps, lights) equals the Run's, for the same files, scheduler and seed; 15 starts of
    the five adversarial families (a robot on its target's column, far apart, symmetric with robots on
    the axis, …) × 5 schedulers × 2 seeds: 150 runs."""
    case = generate(family, case_seed, far=40)
    robots, pattern = _files(tmp_path, case)
    for scheduler in AUTOMATIC:
        for seed in (0, 7):
            cli = _cli_json(
                capsys, "run", "--robots", str(robots), "--pattern", str(pattern),
                "--scheduler", scheduler, "--seed", str(seed), "--json",
            )  # fmt: skip
            r = apf_viz.run(robots, pattern, scheduler=scheduler, seed=seed)
            assert r.as_dict() == cli, (family, case_seed, scheduler, seed)


def test_run_takes_points_files_and_shipped_names_alike(tmp_path):
    case = generate("on-column", 2, far=30)
    robots, pattern = _files(tmp_path, case)
    by_file = apf_viz.run(robots, pattern, seed=4)
    by_points = apf_viz.run(case.robots, case.pattern, seed=4)
    # The points alone carry no y_up: the flips are then the seed's (as for a file without y_up).
    by_points_flipped = apf_viz.run(robots, case.pattern, seed=4)
    assert by_file.as_dict() == by_points_flipped.as_dict()
    assert by_points.engine.y_up != tuple(case.y_up) or by_points.as_dict() == by_file.as_dict()
    shipped = apf_viz.run("sym-call-7", "cup-7", seed=3)
    assert (shipped.outcome, shipped.k, shipped.D) == ("formed", 7, 7)


def test_the_events_table_is_the_run_event_by_event():
    r = apf_viz.run([(0, 0), (3, 0), (5, 1), (2, 2)], [(0, 0), (1, 0), (2, 0), (3, 0)], scheduler="ssync")
    rows = r.event_rows()
    assert len(rows) == r.events == len(r.events_table())
    assert [row["event"] for row in rows] == list(range(1, r.events + 1))
    events = r.engine.history.events()
    for row, e in zip(rows, events, strict=True):
        assert (row["robot"], row["phase"]) == (e.robot, e.phase)
        if e.phase == "move" and not e.collision:
            assert (row["x"], row["y"]) == tuple(e.to)  # where it went
        if e.phase == "compute":
            assert row["light"] == e.light and row["rule"] == (e.rule_id or e.rule)
    assert r.positions_at(r.events) == r.final
    assert r.positions_at(0) == [(0, 0), (3, 0), (5, 1), (2, 2)]
    halfway = r.events // 2
    moved = {row["robot"]: (row["x"], row["y"]) for row in rows[:halfway]}
    assert all(r.positions_at(halfway)[i] == p for i, p in moved.items())
    with pytest.raises(InputError, match="events 0 to"):
        r.positions_at(r.events + 1)


def test_a_saved_trace_replays_to_the_same_run(tmp_path, capsys):
    r = apf_viz.run("sym-call-7", "cup-7", scheduler="stale-first", seed=5)
    path = tmp_path / "run.jsonl"
    r.save_trace(path)
    header, events = load_trace(path)
    assert len(events) == r.events and header.scheduler == "stale-first" and header.seed == 5
    capsys.readouterr()
    assert main(["replay", "--trace", str(path)]) == 0  # formed
    assert "formed" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("robots", "pattern", "algorithm", "flips"),
    [
        (
            [(0, 0), (0, 1), (0, 2), (0, 4)],
            [(0, 1), (1, 1), (2, 1), (1, 0)],
            "apf-opaque-grid-literal",
            "all",
        ),
        ([(0, 0), (2, 0), (1, 1)], [(0, 0), (1, 0), (2, 0)], "apf-opaque-grid", "file"),
    ],
)
def test_check_has_the_command_lines_verdict_and_its_counterexample_replays(
    tmp_path, capsys, robots, pattern, algorithm, flips
):
    r_file, p_file = tmp_path / "r.json", tmp_path / "p.json"
    r_file.write_text(json.dumps({"robots": robots}))
    p_file.write_text(json.dumps({"points": pattern}))
    cex = tmp_path / "cex.jsonl"
    capsys.readouterr()
    main(
        ["check", "--robots", str(r_file), "--pattern", str(p_file), "--algorithm", algorithm,
         "--flips", flips, "--json", "--counterexample", str(cex)]
    )  # fmt: skip
    cli = json.loads(capsys.readouterr().out)
    v = apf_viz.check(r_file, p_file, algorithm=algorithm, flips=flips)
    assert (v.verdict, v.states, v.transitions, list(v.y_up), len(v.schedule)) == (
        cli["verdict"], cli["states"], cli["transitions"], cli["y_up"], cli["schedule_length"]
    )  # fmt: skip
    if v.failed:
        assert v.replay().outcome == v.verdict == "collision"
        mine = tmp_path / "mine.jsonl"
        v.save_counterexample(mine)
        assert mine.read_text() == cex.read_text()
    else:
        with pytest.raises(InputError, match="no counterexample"):
            v.replay()


def test_sweep_is_the_command_lines_table(tmp_path, capsys):
    out = tmp_path / "cli.parquet"
    main(
        ["sweep", "--ks", "3,5", "--seeds", "0-2", "--schedulers", "async,fsync", "--workers", "1",
         "--out", str(out)]
    )  # fmt: skip
    from apf_viz.sweeps import read_results

    key = ["k", "seed", "scheduler"]
    cli = sorted(read_results(out), key=lambda r: [r[c] for c in key])
    table = apf_viz.sweep(ks=[3, 5], seeds=range(3), schedulers=["async", "fsync"], workers=1)
    mine = sorted(table.to_dict("records"), key=lambda r: [r[c] for c in key])
    assert len(mine) == len(cli) == 12
    for a, b in zip(mine, cli, strict=True):
        a.pop("wall_s"), b.pop("wall_s")
        assert a == b


def test_bad_inputs_are_one_line_errors_and_seeds_are_never_negative():
    for call, said in [
        (lambda: apf_viz.run("no-such-start", "cup-7"), "no such file, and no shipped robots"),
        (lambda: apf_viz.run("sym-call-7", "cup-7", seed=-1), "seeds are integers, 0 or more"),
        (lambda: apf_viz.run("sym-call-7", "cup-7", scheduler="manual"), "choose from"),
        (lambda: apf_viz.run([(0, 0), (1, 0.5)], [(0, 0), (1, 0)]), "valid integer"),
        (lambda: apf_viz.run("unsolvable-4", "block-6"), "unsolvable start|points"),
        (lambda: apf_viz.check("sym-call-7", "cup-7", flips="some"), "choose all or file"),
        (lambda: apf_viz.sweep(ks=[3], seeds=[-2]), "seeds are whole numbers, 0 or more"),
    ]:
        with pytest.raises(InputError, match=said):
            call()


def _blocks(text: str) -> list[tuple[str, str]]:
    """docs/API.md's fenced blocks in order: (info string, code)."""
    return re.findall(r"```([^\n]*)\n(.*?)```", text, flags=re.S)


def test_every_example_of_the_api_doc_runs_as_written_in_an_empty_folder(tmp_path, monkeypatch):
    """Python blocks run in one namespace, in order; the plug-in's file is written where the doc says,
    and its command is run there, exactly as written, with the installed ``apf-viz``."""
    monkeypatch.chdir(tmp_path)
    namespace: dict = {}
    ran = []
    for info, code in _blocks((ROOT / "docs" / "API.md").read_text()):
        if info.startswith("python file="):
            (tmp_path / info.split("=", 1)[1]).write_text(code)
        elif info == "python":
            exec(compile(code, "docs/API.md", "exec"), namespace)
        elif info == "sh":
            (command,) = code.strip().splitlines()
            assert command.startswith("apf-viz ")
            script = Path(sys.executable).with_name("apf-viz")
            done = subprocess.run(
                [str(script), *command.split()[1:]], cwd=tmp_path, capture_output=True, text=True
            )
            assert done.returncode == 1, done.stderr  # ran, not formed: every lamp on, nobody moves
            assert done.stdout.startswith("stuck:") and "cannot load" not in done.stderr, done
        else:
            continue
        ran.append(info)
    assert ran.count("python") >= 9 and "sh" in ran and "python file=mylamp.py" in ran
    assert (tmp_path / "run.jsonl").is_file() and (tmp_path / "cex.jsonl").is_file()


def test_a_plugin_module_the_current_folder_lacks_is_one_line_saying_where_it_looked(tmp_path):
    script = Path(sys.executable).with_name("apf-viz")
    done = subprocess.run(
        [str(script), "run", "--robots", "sym-call-7", "--pattern", "cup-7", "--algorithm", "mylamp:Lamp"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
    )
    assert done.returncode == 2
    (line,) = done.stderr.strip().splitlines()[-1:]
    assert "No module named 'mylamp'" in line and "current folder" in line and "mylamp.py" in line


def test_the_notebook_runs_top_to_bottom(tmp_path):
    """docs/notebooks/first-steps.py, as a kernel runs it (its sweep's workers do not import it again)."""
    notebook = ROOT / "docs" / "notebooks" / "first-steps.py"
    env = {**os.environ, "MPLBACKEND": "Agg"}
    done = subprocess.run(
        [sys.executable, "-c", f"import runpy; runpy.run_path({str(notebook)!r}, run_name='notebook')"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        env=env,
        timeout=600,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    assert "collision after" in done.stdout
    assert (tmp_path / "moves-against-kD.png").stat().st_size > 5_000


def test_the_docstrings_examples_hold():
    import doctest

    import apf_viz.api.checks
    import apf_viz.api.runs
    import apf_viz.api.sweeps

    for module in (apf_viz.api.runs, apf_viz.api.checks, apf_viz.api.sweeps):
        failed, tried = doctest.testmod(module, raise_on_error=False, verbose=False)
        assert tried and not failed, module.__name__


@pytest.mark.browser
def test_a_run_shown_in_a_notebook_cell_plays_in_a_browser_from_disk(browser, tmp_path):
    """``Run.show()``'s cell output, as a notebook puts it in its page: viser's player in the frame draws
    the run and plays it, with every request off the disk refused (nothing fetched)."""
    import numpy as np
    from PIL import Image

    from tests.test_ui_browser import offline_context  # here: that module needs playwright

    r = apf_viz.run("sym-call-7", "cup-7", seed=3)
    page_file = tmp_path / "notebook.html"
    page_file.write_text(f"<!doctype html><html><body><h1>Out[1]:</h1>{r.show()._repr_html_()}</body></html>")
    context, refused = offline_context(browser, ("file:", "about:", "data:", "blob:"))
    page = context.new_page()
    try:
        page.goto(page_file.as_uri())
        cell = page.frame_locator("iframe")
        cell.locator("canvas").first.wait_for(timeout=60_000)
        field = cell.locator("input.mantine-NumberInput-input").first
        field.wait_for(timeout=60_000)
        start = float(field.input_value())
        deadline = time.time() + 30
        while float(field.input_value()) <= start and time.time() < deadline:
            time.sleep(0.2)
        assert float(field.input_value()) > start  # it plays
        from io import BytesIO

        shot = np.asarray(Image.open(BytesIO(cell.locator("canvas").first.screenshot())).convert("RGB"))
        assert shot.std() > 5  # it draws
        assert refused == []
    finally:
        context.close()


def test_dir_and_tab_completion_offer_the_library_not_the_modules_it_uses():
    names = dir(apf_viz)
    assert {"run", "sweep", "check", "hunt", "Run", "Verdict"} <= set(names)
    assert not {"signal", "contextlib", "os", "sys", "TYPE_CHECKING"} & set(names)


def test_a_run_has_the_attributes_its_repr_shows_and_counts_in_words():
    r = apf_viz.run("one-on-L1-3", "corner-3", seed=2, scheduler="fsync")
    assert (r.algorithm, r.scheduler, r.seed) == ("apf-opaque-grid", "fsync", 2)
    text = repr(r)
    assert f"{r.algorithm}, fsync, seed 2" in text and " 1 moves" not in text and " 1 events" not in text
    from apf_viz.api.runs import _count

    assert (_count(1, "move"), _count(2, "move"), _count(1200, "event")) == (
        "1 move",
        "2 moves",
        "1,200 events",
    )


def test_every_table_without_pandas_is_one_line_naming_the_extra(monkeypatch):
    """pandas is the notebook extra: a run's events, a sweep and a hunt without it say so in the same
    words (api/tables.py), before any work."""
    from apf_viz.core.formats import InputError

    r = apf_viz.run("one-on-L1-3", "corner-3", seed=2)
    monkeypatch.setitem(sys.modules, "pandas", None)  # `import pandas` now fails as if it were missing
    for call, what in (
        (r.events_table, "a table"),
        (lambda: apf_viz.sweep(ks=[4], seeds=[0], workers=1), "sweep's table"),
        (lambda: apf_viz.hunt(ks=[4], count=1, workers=1), "hunt's table"),
    ):
        with pytest.raises(InputError) as e:
            call()
        install = "pip install 'apf-viz[notebook]' (in a checkout: pip install -e '.[notebook]')"
        assert str(e.value) == f"{what} needs pandas: {install}"
