"""``check --worst``: the most moves (events) any adversary can force before FORMED, exactly, on small
starts. The schedule it writes replays to exactly that count; the partial-order reduction never changes
the answer (generated starts, every scheduler family the explorer has); and no run of any built-in
scheduler, on any seed tried, ever costs more (so a maximisation that is not one fails here)."""

from __future__ import annotations

import json
import random
import subprocess
import sys

import pytest

from apf_viz.algorithms import get_algorithm
from apf_viz.core.engine import Engine
from apf_viz.core.schedulers import AUTOMATIC, make_scheduler, step_rng
from apf_viz.core.symmetry import unsolvable_axis
from apf_viz.explore.check import all_flips
from apf_viz.explore.small_starts import box_starts
from apf_viz.explore.worst import worst

ALGORITHM = get_algorithm("apf-opaque-grid")
SHIPPED = [
    ("one-on-L1-3", "corner-3", "all"),
    ("vertical-line-4", "tee-4", "file"),
    ("robots-on-K-5", "hook-5", "file"),
]


def _cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "apf_viz.cli", *args], capture_output=True, text=True)


@pytest.mark.parametrize(("robots", "pattern", "flips"), SHIPPED)
@pytest.mark.parametrize("measure", ["moves", "events"])
def test_the_worst_schedule_of_a_shipped_start_replays_to_exactly_its_count(
    tmp_path, robots, pattern, flips, measure
):
    out = tmp_path / "worst.jsonl"
    files = ["--robots", robots, "--pattern", pattern]
    found = _cli("check", *files, "--flips", flips, "--worst", measure, "--schedule-out", str(out), "--json")
    assert found.returncode == 0, found.stderr
    said = json.loads(found.stdout)
    assert said["verdict"] == "worst" and said["worst"] > 0
    ran = _cli("run", *files, "--schedule", str(out), "--json")
    summary = json.loads(ran.stdout)
    assert summary["outcome"] == "formed" and summary[measure] == said["worst"]


def _generated(k: int, n: int, seed: int) -> list[list[tuple[int, int]]]:
    starts = [s for s in box_starts(k, 4, True) if unsolvable_axis(s) is None]
    random.Random(seed).shuffle(starts)
    return starts[:n]


def _most_any_scheduler(start, pattern, y_up, measure: str, seeds: int) -> int:
    """The most ``measure`` any built-in automatic scheduler reached, over ``seeds`` seeds each."""
    most = 0
    for name in AUTOMATIC:
        scheduler = make_scheduler(name)
        for seed in range(seeds):
            e = Engine(start, pattern, ALGORITHM, y_up=y_up, max_events=100_000)
            while not e.finished:
                e.apply(scheduler.choose(e, step_rng(seed, e.step_index)))
            if e.outcome == "formed":
                most = max(most, e.state.moves if measure == "moves" else e.state.events)
    return most


@pytest.mark.parametrize("scheduler", ["async", "ssync", "fsync"])
def test_the_reduction_never_changes_the_worst_and_no_scheduler_run_beats_it(scheduler):
    pattern = [(0, 0), (1, 0), (2, 0)]
    checked = 0
    for start in _generated(3, 5, seed=11):
        y_up = (True, False, True)
        for measure in ("moves", "events"):
            reduced = worst(ALGORITHM, start, pattern, [y_up], measure, scheduler=scheduler)
            full = worst(ALGORITHM, start, pattern, [y_up], measure, scheduler=scheduler, reduction=False)
            assert (reduced.verdict, reduced.value) == (full.verdict, full.value), (start, measure)
            if reduced.verdict != "worst":
                continue
            checked += 1
            if scheduler == "async":  # every built-in scheduler's run is one of the ASYNC schedules
                assert _most_any_scheduler(start, pattern, y_up, measure, seeds=4) <= reduced.value
    assert checked >= 3  # the comparison was made, not skipped


def test_k4_reduced_and_unreduced_agree_on_generated_starts():
    pattern = [(0, 0), (1, 0), (2, 0), (3, 0)]
    for start in _generated(4, 2, seed=5):
        a = worst(ALGORITHM, start, pattern, [(True,) * 4], "moves", max_states=400_000)
        b = worst(ALGORITHM, start, pattern, [(True,) * 4], "moves", max_states=400_000, reduction=False)
        assert (a.verdict, a.value) == (b.verdict, b.value) or "budget" in (a.verdict, b.verdict)


def test_no_maximum_where_the_plain_search_fails():
    literal = get_algorithm("apf-opaque-grid-literal")
    start, corner = [(0, 0), (0, 3), (2, 1)], [(0, 1), (0, 0), (1, 0)]
    found = worst(literal, start, corner, all_flips(3), "moves")
    assert found.verdict == "collision" and found.value is None and "no maximum" in found.detail


@pytest.mark.parametrize("scheduler", ["ssync", "fsync"])
def test_a_synchronous_worst_replays_to_exactly_its_count_on_generated_starts(scheduler):
    """A round that only lights robots and leaves everyone quiet ends the run after its Computes (the
    engine never makes the Moves that would all stay): the worst counts it so, and its schedule replays
    to the very count."""
    from apf_viz.explore.worst import worst_schedule_text

    replayed = 0
    for n, start in enumerate([*_generated(3, 8, seed=5), [(0, 0), (0, 1), (2, 0)]]):
        pattern = [(0, 1), (0, 0), (1, 0)] if n % 2 else [(0, 0), (1, 0), (2, 0)]
        y_up = (n % 2 == 0, True, n % 3 == 0)
        for measure in ("moves", "events"):
            found = worst(ALGORITHM, start, pattern, [y_up], measure, scheduler=scheduler)
            if found.verdict != "worst":
                continue
            _, moves, events = worst_schedule_text(ALGORITHM, start, pattern, found, scheduler)
            assert (moves if measure == "moves" else events) == found.value, (start, measure)
            replayed += 1
    assert replayed >= 8


def test_worst_reports_progress_as_it_goes_not_only_every_20000_states(monkeypatch):
    """On a far start a state is slow (a robot's walk is a chain of them) and 20,000 states took minutes
    of silence: the search also reports every PROGRESS_EVERY seconds (here 0, so at every state)."""
    import apf_viz.explore.explorer as explorer_module

    monkeypatch.setattr(explorer_module, "PROGRESS_EVERY", 0.0)
    said: list[int] = []
    found = worst(
        ALGORITHM, [(0, 0), (0, 3), (2, 1)], [(0, 1), (0, 0), (1, 0)], [(True, True, False)], "events",
        progress=lambda states, frontier, seconds: said.append(states),
    )  # fmt: skip
    assert found.verdict == "worst" and len(said) > 10 and said == sorted(said)


def test_a_check_worst_schedule_loaded_on_the_page_says_what_it_is_and_its_moves_per_kD(tmp_path, capsys):
    """``check --worst --schedule-out``'s file names the exact worst in its header, as the adversary's
    names its worst found: Load the worst found then shows the moves/(k·D) line for it too; the header
    names the y-axes it used, and for robots given without them check and adversary draw the same ones
    by default (seed 1 both)."""
    from apf_viz.cli import main
    from apf_viz.core.schedule import load_schedule
    from apf_viz.ui.panels.adversary import found_words
    from apf_viz.workbench.session.demo import demo_session

    robots, pattern = tmp_path / "r.json", tmp_path / "p.json"
    robots.write_text(json.dumps({"robots": [[0, 0], [2, 0], [2, 2]]}))  # no y_up: the seed draws them
    pattern.write_text(json.dumps({"points": [[0, 0], [1, 0], [2, 0]]}))
    files = ["--robots", str(robots), "--pattern", str(pattern)]
    out = tmp_path / "worst.schedule"
    main(["check", *files, "--worst", "moves", "--schedule-out", str(out)])
    schedule = load_schedule(out)
    assert schedule.found is not None and schedule.found.by == "check" and schedule.y_up is not None
    session = demo_session()
    session.load_robots("r.json", robots.read_bytes())
    session.load_pattern("p.json", pattern.read_bytes())
    session.load_schedule("worst.schedule", out.read_bytes())
    while session.step():
        pass
    said = found_words(session.view())
    value = schedule.found.value
    assert f"The worst any schedule forces, by apf-viz check --worst: {value} moves" in said
    assert f"moves/(k·D) = {value / 9:.3f}" in said and "FORMED" in said  # k = D = 3
    adversary = tmp_path / "adversary.schedule"
    main(["adversary", *files, "--budget", "4", "--schedule-out", str(adversary)])
    assert load_schedule(adversary).y_up == schedule.y_up


def test_the_largest_exact_worst_docs_adversary_states_is_the_checks():
    """docs/ADVERSARY.md's largest moves/(k·D): 28 moves (3.111 per k·D) over every schedule and flip."""
    import apf_viz

    w = apf_viz.check(
        [(0, 0), (0, 2), (2, 1)], [(0, 0), (0, 1), (0, 2)], worst="moves", flips="all", progress=False
    )
    assert (w.verdict, w.value, w.k * w.D) == ("worst", 28, 9) and w.replay().moves == 28
