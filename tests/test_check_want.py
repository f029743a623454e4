"""``check --want``: one kind of failure looked for past the others. A deadlock the first violation would
hide is found; none of a kind is "absent" exactly where the plain search verifies; every schedule found
replays to its kind in the real engine (generated small starts, every scheduler family the explorer has)."""

from __future__ import annotations

import json
import random
import subprocess
import sys
from pathlib import Path

import pytest

from apf_viz.algorithms import get_algorithm
from apf_viz.cli.check import WANTED as CLI_WANTED
from apf_viz.core.symmetry import unsolvable_axis
from apf_viz.explore.check import all_flips, check, counterexample_engine
from apf_viz.explore.explorer import WANTED
from apf_viz.explore.small_starts import box_starts

DEMOS = Path(__file__).resolve().parent.parent / "demo_patterns"
THREE_WAYS = [(0, 0), (0, 3), (2, 1)]  # demo_patterns/starts/three-ways-to-fail-3.json
CORNER = [(0, 1), (0, 0), (1, 0)]
LITERAL = get_algorithm("apf-opaque-grid-literal")


def test_the_command_line_offers_the_kinds_the_explorer_looks_for():
    assert CLI_WANTED == WANTED


def test_a_deadlock_hidden_behind_the_first_collision_is_found_and_replays():
    first, _ = check(LITERAL, THREE_WAYS, CORNER, all_flips(3), "async", 2_000_000, progress=False)
    assert first.verdict == "collision"  # what check says without --want: it stops here
    for kind in ("deadlock", "livelock"):
        found, y_up = check(
            LITERAL, THREE_WAYS, CORNER, all_flips(3), "async", 2_000_000, progress=False, want=kind
        )
        assert found.verdict == kind
        e = counterexample_engine(LITERAL, THREE_WAYS, CORNER, y_up, "async", found)
        if kind == "deadlock":
            assert e.outcome == "stuck"  # the real engine ends where the explorer's schedule says
        else:
            assert e.outcome is None and not e.finished  # twice round the loop, still going


def _generated(k: int, n: int, seed: int) -> list[list[tuple[int, int]]]:
    starts = [s for s in box_starts(k, 4, True) if unsolvable_axis(s) is None]
    random.Random(seed).shuffle(starts)
    return starts[:n]


@pytest.mark.slow
@pytest.mark.parametrize("scheduler", ["async", "ssync", "fsync"])
@pytest.mark.parametrize("algorithm", ["apf-opaque-grid", "apf-opaque-grid-literal"])
def test_want_agrees_with_the_plain_search_on_generated_starts(scheduler, algorithm):
    """Where the plain search verifies, every kind is absent; where it finds a kind, --want of that kind
    finds one too (not necessarily the same schedule), and each schedule replays to its kind."""
    alg = get_algorithm(algorithm)
    compared = 0
    for start in _generated(3, 6, seed=len(scheduler)):
        pattern = [(0, 0), (1, 0), (2, 0)]
        y_up = (True, False, True)
        plain, _ = check(alg, start, pattern, [y_up], scheduler, 200_000, progress=False)
        if plain.verdict == "budget":
            continue
        for kind in WANTED:
            got, _ = check(alg, start, pattern, [y_up], scheduler, 150_000, progress=False, want=kind)
            if got.verdict == "budget":
                continue
            compared += 1
            if plain.verdict == "verified":
                assert got.verdict == "absent", (start, kind, got.detail)
            elif plain.verdict == kind:
                assert got.verdict == kind, (start, kind)
            if got.verdict in ("collision", "deadlock"):
                e = counterexample_engine(alg, start, pattern, y_up, scheduler, got)
                assert e.outcome == ("stuck" if kind == "deadlock" else "collision"), (start, kind)
    assert compared >= 8  # searches that ended, compared: not all skipped for their budget


def test_cli_check_want_says_what_it_found_or_that_none_exists(tmp_path):
    pattern = tmp_path / "corner.json"
    pattern.write_text(json.dumps({"points": CORNER}))
    start = DEMOS / "starts" / "three-ways-to-fail-3.json"
    base = [sys.executable, "-m", "apf_viz.cli", "check", "--robots", str(start), "--pattern", str(pattern)]
    out = tmp_path / "deadlock.jsonl"
    literal = ["--algorithm", "apf-opaque-grid-literal"]
    p = subprocess.run(
        [*base, *literal, "--want", "deadlock", "--counterexample", str(out), "--json"],
        capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    said = json.loads(p.stdout)
    assert p.returncode == 1 and said["verdict"] == "deadlock" and said["want"] == "deadlock"
    assert out.exists()
    p = subprocess.run([*base, "--want", "collision"], capture_output=True, text=True, timeout=600)
    assert p.returncode == 0 and p.stdout.startswith("absent:") and "no collision in any schedule" in p.stdout


def test_want_deadlock_says_a_deadlock_as_soon_as_it_reaches_one_and_it_replays(tmp_path):
    """A deadlock is checked as each state is found (the goal of the search), not after the whole graph:
    on this start of the literal paper a breadth-first search ran out of a million states before."""
    robots, y_up = [(0, 0), (0, 1), (0, 2), (0, 4)], (True, False, True, True)
    pattern = [(0, 1), (1, 1), (2, 1), (1, 0)]
    found, flips = check(
        LITERAL, robots, pattern, [y_up], "async", 1_000_000, progress=False, want="deadlock"
    )
    assert found.verdict == "deadlock" and found.states < 100_000
    e = counterexample_engine(LITERAL, robots, pattern, flips, "async", found)
    assert e.outcome == "stuck"
