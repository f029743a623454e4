"""The explorer's partial-order reduction (docs/VERIFICATION.md): it reaches every configuration the full
search reaches, gives the same verdict on the corpus, and `check` still reports the shortest
counterexample of all."""

from __future__ import annotations

from collections import deque

import pytest

from apf_viz.algorithms import get_algorithm
from apf_viz.algorithms.apf_opaque_grid.resolutions import RESOLUTIONS
from apf_viz.explore.check import all_flips, check, counterexample_engine, explore
from apf_viz.explore.explorer import Explorer
from tests.test_explorer import Stay, StepUpIfFree, Toggle


def _reachable(explorer: Explorer) -> tuple[set, set, int]:
    """(configurations, violations, states) of the explored graph, by a plain search of successors."""
    start = explorer.initial()
    seen = {start}
    configurations, violations = set(), set()
    queue = deque([start])
    while queue:
        st = queue.popleft()
        configurations.add(explorer.space.configuration(st))
        for _, nxt in explorer.successors(st):
            if isinstance(nxt, str):
                violations.add(nxt.split(":")[0])
                continue
            if nxt not in seen:
                seen.add(nxt)
                queue.append(nxt)
    return configurations, violations, len(seen)


GRAPHS = [
    ("apf-opaque-grid", [(0, 0), (2, 1), (3, -1)], [True, False, True]),
    ("apf-opaque-grid", [(0, 0), (0, 1), (1, 0)], [False, True, True]),
    ("apf-opaque-grid", [(0, 0), (1, 2)], [True, False]),
    ("apf-opaque-grid-literal", [(0, 0), (1, 0)], [True, True]),
    ("apf-opaque-grid+merge(leader1=decider)", [(0, 0), (0, 1), (0, 2)], [True, True, False]),
]


@pytest.mark.parametrize(("name", "start", "y_up"), GRAPHS)
def test_the_reduced_graph_reaches_every_configuration_of_the_full_one(name, start, y_up):
    pattern = [(i, 0) for i in range(len(start))]
    algorithm = get_algorithm(name)
    full = _reachable(Explorer(algorithm, start, pattern, y_up))
    reduced = _reachable(Explorer(algorithm, start, pattern, y_up, reduction=True))
    assert reduced[0] == full[0]  # the same positions and lights, so the same deadlocks and patterns
    assert reduced[1] == full[1]  # the same kinds of violating transition
    assert reduced[2] < full[2]


CORPUS = [
    # (algorithm, start, pattern, flips, verdict)
    (StepUpIfFree(), [(0, 0), (0, 2)], [(0, 0), (0, 1)], [True, False], "collision"),
    (Stay(), [(0, 0), (2, 0)], [(0, 0), (1, 0)], [True, True], "deadlock"),
    (Toggle(), [(0, 0), (2, 0)], [(0, 0), (0, 2)], [True, True], "livelock"),
    ("apf-opaque-grid-literal", [(0, 0), (1, 0)], [(0, 0), (0, 1)], [True, True], "livelock"),
    ("apf-opaque-grid", [(0, 0), (0, 2)], [(0, 0), (1, 0)], [True, True], "livelock"),  # unsolvable
    ("apf-opaque-grid", [(0, 0), (2, 1), (3, -1)], [(0, 0), (1, 0), (2, 0)], [True] * 3, "verified"),
    ("apf-opaque-grid+merge(decider=leader1)", [(0, 0), (1, 1)], [(0, 0), (1, 0)], [True, True], "deadlock"),
    ("apf-opaque-grid+merge(off=terminal1)", [(0, 0), (1, 1)], [(0, 0), (1, 0)], [True, True], "escape"),
]  # fmt: skip


@pytest.mark.parametrize(("algorithm", "start", "pattern", "y_up", "verdict"), CORPUS)
def test_verdicts_and_shortest_counterexamples_are_unchanged(algorithm, start, pattern, y_up, verdict):
    algorithm = get_algorithm(algorithm) if isinstance(algorithm, str) else algorithm
    full = Explorer(algorithm, start, pattern, y_up).run()
    reduced = Explorer(algorithm, start, pattern, y_up, reduction=True).run()
    assert full.verdict == reduced.verdict == verdict
    assert reduced.states <= full.states
    shortest = explore(algorithm, start, pattern, y_up, scheduler="async", max_states=1_000_000)
    assert shortest.verdict == verdict
    assert shortest.schedule == full.schedule and shortest.loop_start == full.loop_start
    if verdict in ("collision", "deadlock"):
        assert counterexample_engine(algorithm, start, pattern, y_up, "async", reduced).outcome is not None


def test_the_lockstep_escape_is_found_by_the_reduced_search_and_replays():
    """test_explorer's finding without L2 (the full search needs up to 400,000 states for it)."""
    without_l2 = get_algorithm("apf-opaque-grid@" + ",".join(r for r in RESOLUTIONS if r != "L2"))
    start, pattern = [(0, 0), (0, 2), (1, 0), (1, 3)], [(0, 0), (1, 0), (2, 0), (3, 0)]
    reduced = Explorer(without_l2, start, pattern, [True] * 4, max_states=400_000, reduction=True).run()
    assert reduced.verdict == "escape"
    e = counterexample_engine(without_l2, start, pattern, [True] * 4, "async", reduced)
    robot, at = reduced.detail.removeprefix("escape: robot ").split(" left the box at ")
    assert str(tuple(e.current_points()[int(robot)])) == at  # the engine reaches the point outside the box


def test_check_with_and_without_the_reduction_over_every_flip():
    algorithm = get_algorithm("apf-opaque-grid")
    start, pattern = [(0, 0), (0, 1), (1, 3)], [(0, 0), (1, 0), (2, 0)]
    full, _ = check(algorithm, start, pattern, all_flips(3), "async", 10**6, False, reduction=False)
    reduced, _ = check(algorithm, start, pattern, all_flips(3), "async", 10**6, False)
    assert full.verdict == reduced.verdict == "verified"
    assert reduced.states * 3 < full.states  # measured: 5–6× fewer on k = 3 starts


def test_no_reduction_under_synchronous_schedulers():
    algorithm = get_algorithm("apf-opaque-grid")
    start, pattern = [(0, 0), (1, 2)], [(0, 0), (1, 0)]
    for scheduler in ("ssync", "fsync"):
        a = Explorer(algorithm, start, pattern, [True, False], scheduler=scheduler).run()
        b = Explorer(algorithm, start, pattern, [True, False], scheduler=scheduler, reduction=True).run()
        assert (a.verdict, a.states) == (b.verdict, b.states)
