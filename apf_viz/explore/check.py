"""`apf-viz check`: run the explorer over the flips asked for, and turn a failure into a trace file."""

from __future__ import annotations

import itertools
import sys
from collections.abc import Callable, Sequence

from apf_viz.core.algorithm import Algorithm
from apf_viz.core.engine import Engine
from apf_viz.core.files import write_atomic
from apf_viz.core.formats import trace_text
from apf_viz.core.grid import Point
from apf_viz.core.run import trace_header
from apf_viz.explore.explorer import Decisions, Explorer, Result, Wanted, absent_detail


def check(
    algorithm: Algorithm,
    robots: Sequence[Point],
    pattern: Sequence[Point],
    flips: Sequence[Sequence[bool]],
    scheduler: str,
    max_states: int,
    progress: bool | Callable[[int, int, float], None] = True,
    light_semantics: str = "compute",
    reduction: bool = True,
    want: Wanted | None = None,
) -> tuple[Result, tuple[bool, ...]]:
    """Explore each assignment of flips; stop at the first violation (with ``want``: the first of that
    kind, the others passed over). States add up across flips."""
    total_states = total_transitions = 0
    seconds = 0.0
    last: Result | None = None
    decisions = Decisions()  # shared by every flip assignment: a decision depends on its robot's flip only
    for y_up in flips:
        r = explore(
            algorithm,
            robots,
            pattern,
            y_up,
            scheduler=scheduler,
            max_states=max(1, max_states - total_states),
            progress=progress if callable(progress) else say_progress if progress else None,
            light_semantics=light_semantics,
            reduction=reduction,
            decisions=decisions,
            want=want,
        )
        total_states += r.states
        total_transitions += r.transitions
        seconds += r.seconds
        r.states, r.transitions, r.seconds = total_states, total_transitions, seconds
        if want is not None and last is not None and r.verdict == "absent" and last.verdict == "absent":
            r.passed = {
                kind: r.passed.get(kind, 0) + last.passed.get(kind, 0) for kind in r.passed | last.passed
            }
            r.detail = absent_detail(want, r.passed)
        last = r
        if r.verdict not in ("verified", "absent"):
            return r, tuple(y_up)
    assert last is not None
    return last, tuple(flips[-1])


def explore(
    algorithm: Algorithm,
    robots: Sequence[Point],
    pattern: Sequence[Point],
    y_up: Sequence[bool],
    *,
    scheduler: str,
    max_states: int,
    progress: Callable[[int, int, float], None] | None = None,
    light_semantics: str = "compute",
    reduction: bool = True,
    decisions: Decisions | None = None,
    want: Wanted | None = None,
) -> Result:
    """One assignment of flips (``decisions``: what searches from the same start share). With
    ``reduction`` (ASYNC only) the search skips the orders of invisible
    events and finds the same verdict; a violation it finds is searched again without the reduction, so
    the counterexample is the shortest schedule of all, as without it (docs/VERIFICATION.md)."""

    def search(reduce: bool) -> Result:
        return Explorer(
            algorithm,
            robots,
            pattern,
            y_up,
            scheduler=scheduler,  # type: ignore[arg-type]
            max_states=max_states,
            progress=progress,
            light_semantics=light_semantics,  # type: ignore[arg-type]
            reduction=reduce,
            decisions=decisions,
            want=want,
        ).run()

    if want is not None:  # every edge is followed past the failures not wanted: no reduction
        return search(False)
    r = search(reduction)
    if reduction and scheduler == "async" and r.verdict not in ("verified", "budget"):
        r = _shortest(r, search(False))
    return r


def _shortest(reduced: Result, full: Result) -> Result:
    """The full search's counterexample (the shortest) with both searches' effort counted; the reduced
    one's if the full search ran out of states."""
    if full.verdict == "budget":
        reduced.detail += " (the reduced search's schedule: the search for the shortest ran out of states)"
        return reduced
    if full.verdict != reduced.verdict:  # the reduction's argument failed: say so, never hide it
        raise AssertionError(f"reduced search: {reduced.verdict}; full search: {full.verdict}")
    full.states += reduced.states
    full.transitions += reduced.transitions
    full.seconds += reduced.seconds
    return full


def all_flips(k: int) -> list[tuple[bool, ...]]:
    return list(itertools.product((True, False), repeat=k))


def say_progress(states: int, frontier: int, seconds: float) -> None:
    """A search's progress on stderr (``check``, ``check --worst``)."""
    print(
        f"apf-viz check: {states:,} states, frontier {frontier:,}, "
        f"{states / max(seconds, 1e-9):,.0f} states/s",
        file=sys.stderr,
        flush=True,
    )


def counterexample_engine(
    algorithm: Algorithm,
    robots,
    pattern,
    y_up,
    scheduler: str,
    result: Result,
    light_semantics: str = "compute",
) -> Engine:
    """Replay the explorer's schedule in the real engine (a livelock's loop is run twice)."""
    e = Engine(robots, pattern, algorithm, y_up=y_up, max_events=10_000_000, light_semantics=light_semantics)  # type: ignore[arg-type]
    schedule = list(result.schedule)
    if result.loop_start is not None:
        schedule += schedule[result.loop_start :]
    for n, robots_ in enumerate(schedule, 1):
        if e.finished:
            break
        if scheduler == "async":
            e.step(robots_)
        else:
            for _ in range(3):
                if not e.finished:
                    e.step(robots_, round=n)
    return e


def counterexample_text(
    algorithm, robots, pattern, y_up, scheduler, result: Result, light_semantics: str = "compute"
) -> str:
    """The explorer's failing schedule replayed by the real engine, as a trace file's text (its header
    says the verdict and, for a livelock, where the loop starts)."""
    e = counterexample_engine(algorithm, robots, pattern, y_up, scheduler, result, light_semantics)
    options: dict[str, object] = {"verdict": result.verdict, "detail": result.detail}
    if result.loop_start is not None:
        options["loop_starts_at_step"] = result.loop_start
    header = trace_header(e, scheduler, None, options)
    return trace_text(header, e.history.events())


def write_counterexample(
    path, algorithm, robots, pattern, y_up, scheduler, result: Result, light_semantics: str = "compute"
) -> None:
    write_atomic(
        path, counterexample_text(algorithm, robots, pattern, y_up, scheduler, result, light_semantics)
    )
