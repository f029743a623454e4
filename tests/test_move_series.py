"""The live plot's series: checked against the engine's own counters while stepping, seeking and
branching, and thinned to a bounded number of points."""

from __future__ import annotations

from apf_viz.workbench.move_series import MoveSeries
from apf_viz.workbench.session import Session

START = [(0, 0), (0, 2), (1, 0), (1, 3), (3, 1)]
PATTERN = [(0, 0), (1, 0), (2, 0), (3, 0), (4, 0)]


def _run_to_end(s: Session) -> list[tuple[int, int]]:
    """(events, moves) after each step, from the engine's counters: the oracle."""
    totals = [(0, 0)]
    while not s.engine.finished:
        s.step()
        totals.append((s.engine.state.events, s.engine.state.moves))
    return totals


def _expected(totals: list[tuple[int, int]], step: int) -> list[tuple[int, int]]:
    """The start, each step that changed the move count, and the current step."""
    steps = [0] + [i for i in range(1, step + 1) if totals[i][1] != totals[i - 1][1]]
    if steps[-1] != step:
        steps.append(step)
    return [totals[i] for i in steps]


def test_series_matches_the_engine_counters_at_every_step_and_after_seeking_back():
    s = Session(START, PATTERN, y_up=[True, False, True, True, False], seed=4)
    totals = _run_to_end(s)
    assert s.engine.state.outcome == "formed" and totals[-1][1] > 0
    series = MoveSeries(START)
    for step in [*range(len(totals)), 7, 0, len(totals) - 1, 3]:  # forward, then back and forth
        got = series.at(s.engine.history, step)
        assert list(got) == _expected(totals, step), step


def test_a_branch_restarts_the_series_and_it_follows_the_new_history():
    s = Session(START, PATTERN, y_up=[True] * 5, seed=2)
    _run_to_end(s)
    s.seek(12)
    s.set_scheduler("Manual")
    before = s.view().move_series
    s.click(s.engine.current_points()[0])  # a choice from step 12: the history after it is dropped
    s.set_scheduler("ASYNC")
    totals = [(0, 0)]
    for step in range(1, s.engine.history.length + 1):
        s.seek(step)
        totals.append((s.engine.state.events, s.engine.state.moves))
    new = _run_to_end(s)
    totals += new[1:]
    assert s.view().move_series == tuple(_expected(totals, s.engine.step_index))
    assert before[-1] == totals[12]


def test_a_long_series_is_thinned_keeping_the_start_and_the_latest_point():
    s = Session(START, PATTERN, y_up=[True, False, True, True, False], seed=4)
    totals = _run_to_end(s)
    step = len(totals) - 1
    full = _expected(totals, step)
    thin = MoveSeries(START).at(s.engine.history, step, limit=4)
    assert len(full) > 4 and len(thin) <= 4
    assert thin[0] == (0, 0) and thin[-1] == totals[step] and set(thin) <= set(full)
    assert list(thin) == sorted(thin)
