"""The light-budget lab (`apf-viz lights`, docs/LIGHTS.md): its merges and starts, its verdicts, its
table (resumed, refused when foreign), its matrix plot, and the counterexamples it keeps: each replays
to its violation under its merged variant, and the same schedule forms under the unmerged algorithm."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from apf_viz import lights
from apf_viz.algorithms import get_algorithm
from apf_viz.core.formats import InputError, load_trace
from apf_viz.core.run import advance, engine_for_trace, replay
from apf_viz.core.schedule import Schedule, follow, schedule_of_trace
from apf_viz.core.schedulers import make_scheduler
from apf_viz.explore.escape import escape_evidence

ROOT = Path(__file__).resolve().parent.parent
TABLE = ROOT / "docs" / "lights.parquet"  # the lab's full matrix (docs/LIGHTS.md says how it was made)
KEPT = sorted((ROOT / "demo_patterns" / "traces" / "lights").glob("*.jsonl"))


def test_every_ordered_pair_of_lights_is_a_merge_and_bad_ones_are_refused():
    every = lights.merges("apf-opaque-grid")
    assert len(every) == 56 and len({m.variant for m in every}) == 56
    assert [m.name for m in lights.merges("apf-opaque-grid", "leader1=decider, off=call")] == [
        "leader1=decider",
        "off=call",
    ]
    for bad in ("leader1=leader1", "leader1=nope", "leader1", "=off"):
        with pytest.raises(InputError, match="--merges"):
            lights.merges("apf-opaque-grid", bad)
    with pytest.raises(InputError, match="unmerged"):
        lights.merges("apf-opaque-grid+merge(off=call)")
    for bad in ("0-3", "6", "x"):
        with pytest.raises(InputError, match="--ks"):
            lights.parse_ks(bad)


def test_the_starts_are_the_symmetric_ones_with_robots_on_the_axis_then_every_small_start():
    from apf_viz.core.pattern_match import normalise
    from apf_viz.explore.small_starts import STATED_STARTS, axis_symmetric, axis_symmetric_box_starts

    starts = lights.starts_for((1, 2, 3, 4, 5))
    sizes = [len(s) for _, s in starts]
    assert sizes == sorted(sizes)  # fewest robots first: the first counterexample is a small one
    keys = [tuple(normalise(s)) for _, s in starts]
    assert len(set(keys)) == len(keys)  # each start once
    for k in (2, 3, 4, 5):
        mine = [s for _, s in starts if len(s) == k]
        symmetric = axis_symmetric_box_starts(k, 5)
        assert len(symmetric) == {2: 4, 3: 24, 4: 56, 5: 182}[k]
        assert mine[: len(symmetric)] == symmetric  # the hardest first, every one of them
        assert all(axis_symmetric(s) for s in symmetric)
    assert all(tuple(normalise(s)) in set(keys) for s in STATED_STARTS.values())
    # A mirror image is left out only because every flip assignment is explored: it is the same run.
    assert not any(json.loads(n) == [[0, 1], [1, 0]] for n, s in starts if len(s) == 2)


def test_a_broken_merge_keeps_its_counterexample_and_one_never_at_work_is_untested(tmp_path):
    small = lights.starts_for((1, 2))
    broken = lights.explore_merge(
        lights.Merge("apf-opaque-grid", "decider", "leader1"), (1, 2), str(tmp_path), small
    )
    assert broken["verdict"] == "breaks" and broken["violation"].startswith("deadlock")
    assert broken["k"] == 2 and Path(broken["trace"]).is_file() and broken["exercised"] > 0
    # One robot alone never calls: the merge of call is never at work, and nothing is claimed of it.
    alone = lights.explore_merge(
        lights.Merge("apf-opaque-grid", "off", "call"), (1,), str(tmp_path), small[:1]
    )
    assert (alone["verdict"], alone["exercised"], alone["starts"]) == ("untested", 0, 1)
    assert alone["states"] > 0


def test_a_merge_at_work_that_breaks_nowhere_survives_with_its_coverage(tmp_path):
    starts = lights.starts_for((1, 2, 3))[:40]
    row = lights.explore_merge(
        lights.Merge("apf-opaque-grid", "terminal1", "call"), (1, 2, 3), str(tmp_path), starts
    )
    assert row["verdict"] == "survives" and row["exercised"] > 0 and row["starts"] == 40


def test_a_random_run_breaks_a_merge_only_where_the_base_algorithm_forms():
    row = lights.verdict_row(lights.Merge("a", "x", "y"), (1,), "untested", "explorer", "", t0=0.0)
    run = {"algorithm": "a+merge(x=y)", "scheduler": "async", "start": "", "error": "", "trace": "",
           "light_semantics": "compute", "hidden": 3}  # fmt: skip
    stuck = dict(run, seed=1, k=7, outcome="stuck", events=90, start="sym-call-7", scheduler="stale-first",
                 trace="t.jsonl")  # fmt: skip
    runs = [
        dict(run, seed=2, k=6, outcome="formed", events=50),
        stuck,
        dict(run, seed=1, k=7, outcome="stuck", events=9, algorithm="a+merge(x=z)"),
        dict(stuck, algorithm="a", hidden=0, outcome="formed", trace=""),  # the base, on the same run
    ]  # fmt: skip
    folded = lights.fold_random(row, runs)
    assert (folded["verdict"], folded["stage"], folded["random_runs"], folded["random_failed"]) == (
        "breaks",
        "random",
        2,
        1,
    )
    assert folded["violation"] == "stuck" and folded["trace"] == "t.jsonl"
    assert folded["start"] == "sym-call-7, seed 1, stale-first"
    # Where the base algorithm fails too, the failure is not the merge's.
    assert lights.fold_random(row, runs[:3])["verdict"] == "survives"
    assert lights.fold_random(row, runs[:1])["verdict"] == "survives"  # at work in a run: evidence
    never = [dict(runs[0], hidden=0)]
    assert lights.fold_random(row, never)["verdict"] == "untested"  # never at work: nothing claimed


def _cli(*args, cwd):
    return subprocess.run(
        [sys.executable, "-m", "apf_viz.cli", "lights", *args], capture_output=True, text=True, cwd=cwd
    )


def test_the_command_writes_resumes_and_plots_the_matrix(tmp_path):
    args = ["--ks", "1-2", "--merges", "decider=leader1,terminal1=call", "--random", "2", "--workers", "1"]
    first = _cli(*args, "--out", "l.parquet", cwd=tmp_path)
    assert first.returncode == 0, first.stderr
    assert "| decider=leader1 | breaks | explorer | deadlock" in first.stdout
    assert "the base algorithm on 14/14 starts" in first.stderr
    assert "2/2 merges explored, 1 broken" in first.stderr
    rows = lights.read_lights(tmp_path / "l.parquet")
    verdicts = {r["merge"]: r["verdict"] for r in rows}
    assert verdicts["decider=leader1"] == "breaks"
    call = next(r for r in rows if r["merge"] == "terminal1=call")
    assert call["random_runs"] == 2 and f"| terminal1=call | {call['verdict']} |" in first.stdout
    assert call["verdict"] == ("untested" if call["exercised"] + call["random_exercised"] == 0 else
                               "survives" if not call["random_failed"] else "breaks")  # fmt: skip
    base = json.loads((tmp_path / "l-base.json").read_text())
    assert len(base["starts"]) == 14 and {r["verdict"] for r in base["starts"]} == {"verified"}
    assert (tmp_path / "l-traces" / "apf-opaque-grid+merge(decider=leader1).jsonl").is_file()
    # What it wrote beside the table is said, not left to be found.
    assert "apf-viz lights: l.parquet, and beside it l-base.json (stage 0's verdicts" in first.stderr
    assert "l-traces (counterexample traces); l-random.parquet (the random runs)" in first.stderr
    again = _cli(*args, "--out", "l.parquet", cwd=tmp_path)  # everything is in the file: nothing is run
    assert again.returncode == 0 and "merges explored" not in again.stderr
    assert lights.read_lights(tmp_path / "l.parquet") == rows
    plot = subprocess.run(
        [sys.executable, "-m", "apf_viz.cli", "plot", "l.parquet", "--out", "figs"],
        capture_output=True,
        text=True,
        cwd=tmp_path,
    )
    assert plot.returncode == 0, plot.stderr
    assert (tmp_path / "figs" / "light_merges.png").stat().st_size > 10_000


def test_bad_input_is_one_line_and_exit_2(tmp_path):
    (tmp_path / "notes.parquet").write_text("my notes")
    for args, says in [
        (["--merges", "leader1=leader1", "--out", "x.parquet"], "--merges"),
        (["--ks", "7", "--out", "x.parquet"], "--ks"),
        (["--out", "x.csv"], ".parquet"),
        (["--algorithm", "nope", "--out", "x.parquet"], "unknown algorithm"),
        (["--out", "notes.parquet", "--merges", "off=call"], "not a table"),
    ]:
        r = _cli(*args, cwd=tmp_path)
        assert r.returncode == 2 and says in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert (tmp_path / "notes.parquet").read_text() == "my notes"


def _violation_reached(header, events) -> str:
    """Replay the trace under its own (merged) algorithm, checking every event, and say which
    violation it reaches (the explorer's name for it, or the engine's outcome for a random run's)."""
    algorithm = get_algorithm(header.algorithm)
    e = engine_for_trace(header, algorithm)
    replay(e, events)
    verdict = header.options.get("verdict", e.state.outcome)
    if verdict == "collision":
        assert e.state.outcome == "collision"
    elif verdict in ("deadlock", "stuck"):  # a start stuck before any event replays as stuck too
        assert e.state.outcome == "stuck"
        assert all(e.decide(e.look(r)).is_noop(e.state.lights[r]) for r in range(e.k))
    elif verdict == "escape":
        robot, at = header.options["detail"].removeprefix("escape: robot ").split(" left the box at ")
        x, y = e.current_points()[int(robot)]
        assert at.startswith(str((x, y)))
        far = max(max(abs(x - sx), abs(y - sy)) for sx, sy in header.robots)
        assert far > 2 * len(header.robots) + 4  # beyond any margin the explorer gives this start
        # Shown, not assumed: continued by a fair scheduler, the robot is still walking away at the cap
        # (four shipped escapes once stopped at a corner past the box and formed, under every scheduler).
        assert escape_evidence(header, events, algorithm, int(robot)) is not None, "the walk ends"
    elif verdict is None:  # a random run cut by its budget: the robots never stopped
        from apf_viz.core.budget import run_budget

        budget = run_budget([tuple(p) for p in header.robots], [tuple(p) for p in header.pattern])
        assert e.state.events >= budget.max_events or e.state.moves >= budget.max_moves
        verdict = "limit"
    else:
        assert verdict == "livelock" and e.state.outcome is None  # the loop, twice, and not formed
    return verdict


@pytest.mark.parametrize("path", KEPT, ids=[p.stem.split("merge(")[1].split(")")[0] for p in KEPT])
def test_each_kept_counterexample_breaks_its_merge_and_not_the_algorithm(path):
    header, events = load_trace(path)
    assert "+merge(" in header.algorithm
    _violation_reached(header, events)
    base = header.algorithm.split("+merge(")[0]
    lc_atomic = header.light_semantics == "lc-atomic"
    schedule = Schedule(len(header.robots), header.y_up, header.light_semantics)
    for n, line in enumerate(schedule_of_trace(events, lc_atomic), 1):
        schedule.add(n, line)
    e = engine_for_trace(header, get_algorithm(base))
    for _ in follow(e, schedule):
        pass
    assert e.state.outcome in (None, "formed")  # the same schedule breaks nothing
    advance(e, make_scheduler("round-robin"), 1)  # then a fair scheduler, to the end
    assert e.state.outcome == "formed"


def test_the_table_keeps_a_counterexample_for_every_broken_merge_and_nothing_else():
    rows = lights.read_lights(TABLE)
    assert len(rows) == 56 and {r["verdict"] for r in rows} <= {"breaks", "survives", "untested"}
    broken = [r for r in rows if r["verdict"] == "breaks"]
    assert sorted(ROOT / r["trace"] for r in broken) == KEPT
    for r in broken:
        header, _ = load_trace(ROOT / r["trace"])
        assert header.algorithm == f"apf-opaque-grid+merge({r['merge']})"
    verified = json.loads((ROOT / "docs" / "lights-base.json").read_text())["starts"]
    assert len(verified) == len(lights.starts_for((1, 2, 3, 4, 5)))
    explored = sum(v["verdict"] == "verified" for v in verified)
    for r in rows:
        if r["verdict"] in ("survives", "untested"):
            assert r["starts"] == explored and r["random_runs"] == 150 and r["random_failed"] == 0
            assert (r["exercised"] + r["random_exercised"] > 0) == (r["verdict"] == "survives")


def test_a_foreign_table_is_not_taken_for_a_lights_table(tmp_path):
    assert not lights.is_lights_table(tmp_path / "missing.parquet")
    with pytest.raises(InputError):
        lights.read_lights(Path(__file__))


@pytest.mark.slow
def test_ctrl_c_keeps_the_merges_that_finished(tmp_path):
    from tests.sweep_helpers import interrupt_when

    # decider=leader1 breaks on a k = 2 start; terminal1=call runs the whole explorer stage.
    argv = [sys.executable, "-m", "apf_viz.cli", "lights", "--merges", "decider=leader1,terminal1=call",
            "--ks", "1-3", "--workers", "2", "--out", "l.parquet"]  # fmt: skip
    code, err = interrupt_when(argv, tmp_path, rb"1/2 merges explored")
    assert code == 130 and "interrupted; keeping the merges that finished" in err, err[-300:]
    assert "Traceback" not in err
    kept = lights.read_lights(tmp_path / "l.parquet")
    assert [(r["merge"], r["verdict"]) for r in kept] == [("decider=leader1", "breaks")]


def test_a_start_the_base_algorithm_fails_on_is_left_out_and_said(tmp_path):
    """Stage 0: where the algorithm fails unmerged, a merge's failure would say nothing (the literal
    paper's variant livelocks with two robots)."""
    path = tmp_path / "base.json"
    kept = lights.base_verified_starts("apf-opaque-grid-literal", (1, 2), path, 1, None, None)
    said = json.loads(path.read_text())
    failed = [r for r in said["starts"] if r["verdict"] != "verified"]
    assert failed and len(said["starts"]) == len(lights.starts_for((1, 2)))
    assert {name for name, _ in kept} == {r["start"] for r in said["starts"] if r["verdict"] == "verified"}
    assert all(r["detail"] and r["y_up"] for r in failed)
    # Kept beside the table, it is not explored again.
    assert lights.base_verified_starts("apf-opaque-grid-literal", (1, 2), path, 1, None, None) == kept


LEFT_THE_BOX = sorted((ROOT / "tests" / "data").glob("left-the-box-*.jsonl"))


@pytest.mark.parametrize("path", LEFT_THE_BOX, ids=[p.stem.split("box-")[1] for p in LEFT_THE_BOX])
def test_a_robot_that_leaves_the_box_and_stops_is_no_escape(path):
    """The explorer's escapes of four merges, as once shipped (leader1=call, off=decider, off=symmetric,
    terminal1=decider): a robot leaves the box, then stops at its corner a few cells beyond, and every
    fair continuation forms. The lab now looks on instead."""
    from apf_viz.explore.escape import continuations, escaping_robot

    assert len(LEFT_THE_BOX) == 4
    header, events = load_trace(path)
    algorithm = get_algorithm(header.algorithm)
    robot = escaping_robot(header.options["detail"])
    assert escape_evidence(header, events, algorithm, robot) is None
    assert {c.outcome for c in continuations(header, events, algorithm, robot)} == {"formed"}
