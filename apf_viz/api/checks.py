"""Every schedule of a small start from Python: :func:`check` runs ``apf-viz check``'s explorer and returns
a :class:`Verdict`, whose counterexample (if any) is a schedule to read and a run to replay."""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any, Literal, overload

from apf_viz.api.inputs import Points, Start, start_of, whole_number
from apf_viz.api.progress_bars import ProgressBar
from apf_viz.api.runs import Run, _seed, chosen_algorithm, refuse_unsolvable
from apf_viz.core.algorithm import Algorithm
from apf_viz.core.files import write_atomic
from apf_viz.core.formats import InputError
from apf_viz.core.grid import Point
from apf_viz.explore.explorer import Result, Wanted
from apf_viz.explore.worst import MEASURES, Measure

Flips = Literal["all", "file"]


@dataclass(frozen=True)
class Verdict:
    """What the explorer found: :attr:`verdict` is ``verified`` (every schedule forms the pattern),
    ``budget`` (more than ``max_states`` states), or the failure a schedule forces (``collision``,
    ``deadlock``, ``livelock``, ``escape``, …), with :attr:`schedule` (the robots acting at each step,
    from the start) and the flips it needs (:attr:`y_up`)."""

    verdict: str
    states: int
    transitions: int
    seconds: float
    detail: str
    y_up: tuple[bool, ...]
    schedule: tuple[tuple[int, ...], ...] = field(repr=False)
    loop_start: int | None
    _robots: tuple[Point, ...] = field(repr=False)
    _pattern: tuple[Point, ...] = field(repr=False)
    _algorithm: Algorithm = field(repr=False)
    _scheduler: str = field(repr=False)
    _light_semantics: str = field(repr=False)

    @classmethod
    def of(
        cls,
        result: Result,
        y_up: Sequence[bool],
        start: Start,
        algorithm: Algorithm,
        scheduler: str,
        light_semantics: str,
    ) -> Verdict:
        """The explorer's result on ``start`` under the flips ``y_up``."""
        return cls(
            result.verdict,
            result.states,
            result.transitions,
            result.seconds,
            result.detail,
            tuple(y_up),
            tuple(tuple(s) for s in result.schedule),
            result.loop_start,
            tuple(start.robots),
            tuple(start.pattern),
            algorithm,
            scheduler,
            light_semantics,
        )

    @property
    def failed(self) -> bool:
        """Whether a schedule forces a failure: there is a counterexample to replay or save."""
        return self.verdict not in ("verified", "budget", "absent")

    def replay(self) -> Run:
        """The counterexample replayed by the real engine (a livelock's loop twice), as a :class:`Run`
        whose :attr:`Run.outcome` is the failure (a ValueError when there is no counterexample)."""
        if not self.failed:
            raise InputError(f"verdict {self.verdict}: no counterexample to replay")
        from apf_viz.explore.check import counterexample_engine

        engine = counterexample_engine(*self._counterexample())
        start = Start(list(self._robots), list(self.y_up), list(self._pattern), "the start", "the pattern")
        return Run(engine, self._scheduler, 0, start, {})

    def save_counterexample(self, path: str | os.PathLike[str]) -> None:
        """Write the counterexample as a trace file, as ``apf-viz check --counterexample`` does."""
        if not self.failed:
            raise InputError(f"verdict {self.verdict}: no counterexample to write")
        from apf_viz.explore.check import counterexample_text

        write_atomic(os.fspath(path), counterexample_text(*self._counterexample()))

    def _counterexample(self) -> tuple[Any, ...]:
        """What the explorer's counterexample is replayed from (explore/check.py's arguments)."""
        robots, pattern = list(self._robots), list(self._pattern)
        return (
            self._algorithm,
            robots,
            pattern,
            self.y_up,
            self._scheduler,
            self._result(),
            self._light_semantics,
        )

    def _result(self) -> Result:
        return Result(
            self.verdict,  # type: ignore[arg-type]
            self.states,
            self.transitions,
            self.seconds,
            [tuple(s) for s in self.schedule],
            self.loop_start,
            self.detail,
        )


@dataclass(frozen=True)
class Worst:
    """The most moves (or events) any schedule and flips can force before FORMED, exactly, as ``apf-viz
    check --worst`` finds it: :attr:`verdict` ``worst`` with :attr:`value` and :attr:`per_kD`, or why there
    is none (``unbounded``, ``budget``, or the failure a schedule forces; :attr:`value` None). A worst's
    :attr:`schedule` (a schedule file's text, replayed to the same count before it is returned) is what
    :meth:`replay` and ``apf-viz run --schedule`` play."""

    measure: str
    verdict: str
    value: int | None
    k: int
    D: int
    states: int
    seconds: float
    detail: str
    y_up: tuple[bool, ...]
    schedule: str | None = field(repr=False)
    _start: Start = field(repr=False)
    _algorithm: Algorithm = field(repr=False)

    @property
    def per_kD(self) -> float | None:
        """The worst as moves (events) per k·D, the paper's measure of cost."""
        return None if self.value is None else self.value / (self.k * self.D)

    def replay(self) -> Run:
        """The worst schedule played by the real engine, as a :class:`Run` (its moves are :attr:`value`)."""
        return replay_schedule(self.schedule, self._start, self._algorithm, self.verdict)

    def save_schedule(self, path: str | os.PathLike[str]) -> None:
        """Write :attr:`schedule` (``check --worst --schedule-out``'s file)."""
        write_schedule(self.schedule, path, self.verdict)


def replay_schedule(schedule: str | None, start: Start, algorithm: Algorithm, verdict: str) -> Run:
    """A schedule found, played by the real engine from the start it was found on."""
    from apf_viz.api.runs import follow_schedule
    from apf_viz.core.schedule import parse_schedule

    if schedule is None:
        raise InputError(f"verdict {verdict}: no schedule to replay")
    return follow_schedule(start, algorithm, parse_schedule(schedule))


def write_schedule(schedule: str | None, path: str | os.PathLike[str], verdict: str) -> None:
    """Write a schedule found as a schedule file (what :meth:`Worst.save_schedule` writes).

    Args:
        schedule: the schedule file's text; None when the search found none (an InputError).
        path: the file to write.
        verdict: the search's verdict, named in the error when there is no schedule.
    """
    from apf_viz.api.runs import write_file

    if schedule is None:
        raise InputError(f"verdict {verdict}: no schedule to write")
    write_file(path, schedule)


@overload
def check(
    robots: Points,
    pattern: Points,
    *,
    algorithm: str | None = None,
    scheduler: str = "async",
    flips: Flips = "file",
    seed: int = 1,
    max_states: int = 1_000_000,
    light_semantics: str = "compute",
    reduction: bool = True,
    force: bool = False,
    worst: None = None,
    want: Wanted | None = None,
    progress: bool = True,
) -> Verdict:
    """Without ``worst``: the search's :class:`Verdict`."""
    ...


@overload
def check(
    robots: Points,
    pattern: Points,
    *,
    algorithm: str | None = None,
    scheduler: str = "async",
    flips: Flips = "file",
    seed: int = 1,
    max_states: int = 1_000_000,
    light_semantics: str = "compute",
    reduction: bool = True,
    force: bool = False,
    worst: Measure,
    want: None = None,
    progress: bool = True,
) -> Worst:
    """With ``worst`` (``"moves"`` or ``"events"``): the :class:`Worst` instead of a verdict."""
    ...


def check(
    robots: Points,
    pattern: Points,
    *,
    algorithm: str | None = None,
    scheduler: str = "async",
    flips: Flips = "file",
    seed: int = 1,
    max_states: int = 1_000_000,
    light_semantics: str = "compute",
    reduction: bool = True,
    force: bool = False,
    worst: Measure | None = None,
    want: Wanted | None = None,
    progress: bool = True,
) -> Verdict | Worst:
    """Explore every schedule of a small start, as ``apf-viz check`` does: ``flips="all"`` tries every
    assignment of the robots' y-axes, ``"file"`` the robots' own (or the random ones ``seed`` draws).
    Stops at the first failure; the verdict, states and schedule are the command's. ``want`` (collision,
    escape, deadlock, livelock) looks for that failure only (``--want``: verdict ``absent`` when no
    schedule has one); ``worst="moves"`` (or ``"events"``) returns the :class:`Worst` instead, as
    ``--worst``. ``progress``: a bar while it searches.

    >>> v = check([(0, 0), (0, 1), (0, 2), (0, 4)], [(0, 1), (1, 1), (2, 1), (1, 0)],
    ...           algorithm="apf-opaque-grid-literal", flips="all", progress=False)
    >>> v.verdict, len(v.schedule), v.replay().outcome
    ('collision', 41, 'collision')
    """
    from apf_viz.explore.check import all_flips
    from apf_viz.explore.check import check as explore

    start = start_of(robots, pattern)
    seed = _seed(seed)
    _refuse_options(scheduler, flips, max_states, light_semantics, worst, want)
    if not force:
        refuse_unsolvable(start)
    chosen, _ = chosen_algorithm(algorithm)
    assignments = all_flips(len(start.robots)) if flips == "all" else [tuple(start.flips(seed))]
    with ProgressBar("apf-viz check", None, "states", progress) as bar:
        report = _reporter(bar)
        if worst is not None:
            return _worst(start, chosen, assignments, worst, scheduler, max_states, reduction,
                          light_semantics, report)  # fmt: skip
        result, y_up = explore(
            chosen,
            start.robots,
            start.pattern,
            assignments,
            scheduler,
            max_states,
            progress=report,
            light_semantics=light_semantics,
            reduction=reduction,
            want=want,
        )
    return Verdict.of(result, y_up, start, chosen, scheduler, light_semantics)


def _refuse_options(
    scheduler: str, flips: str, max_states: int, light_semantics: str, worst: str | None, want: str | None
) -> None:
    """Every bad option in one line, before any search."""
    from apf_viz.explore.explorer import WANTED

    if scheduler not in ("async", "ssync", "fsync"):
        raise InputError(f"scheduler {scheduler!r}: check explores async, ssync or fsync")
    if flips not in ("all", "file"):
        raise InputError(f"flips {flips!r}: choose all or file")
    whole_number("max_states", max_states)
    if light_semantics not in ("compute", "lc-atomic"):
        raise InputError(f"light_semantics {light_semantics!r}: choose compute or lc-atomic")
    if worst not in (None, *MEASURES):
        raise InputError(f"worst {worst!r}: choose moves or events")
    if want not in (None, *WANTED):
        raise InputError(f"want {want!r}: choose {', '.join(WANTED)}")
    if worst is not None and want is not None:
        raise InputError("worst and want ask different questions: give one")


def _reporter(bar: ProgressBar) -> Callable[[int, int, float], None]:
    def report(states: int, frontier: int, seconds: float) -> None:
        bar.to(states, f"frontier {frontier:,}")

    return report


def _worst(
    start: Start,
    chosen: Algorithm,
    assignments: list[tuple[bool, ...]],
    measure: Measure,
    scheduler: str,
    max_states: int,
    reduction: bool,
    light_semantics: str,
    report: Callable[[int, int, float], None],
) -> Worst:
    """``check --worst``: the maximum, and its schedule replayed to the same count (a claim checked)."""
    from apf_viz.core.budget import paper_D
    from apf_viz.explore.worst import worst, worst_schedule_text

    found = worst(
        chosen, start.robots, start.pattern, assignments, measure,
        scheduler=scheduler, max_states=max_states, reduction=reduction,
        light_semantics=light_semantics, progress=report,
    )  # fmt: skip
    text = None
    if found.verdict == "worst":
        text, moves, events = worst_schedule_text(
            chosen, start.robots, start.pattern, found, scheduler, light_semantics
        )
        replayed = moves if measure == "moves" else events
        if replayed != found.value:  # never hide it: the maximum is a claim the replay checks
            raise AssertionError(f"the worst schedule replays to {replayed} {measure}, not {found.value}")
    return Worst(
        measure, found.verdict, found.value, len(start.robots), paper_D(start.robots, start.pattern),
        found.states, found.seconds, found.detail, tuple(found.y_up), text, start, chosen,
    )  # fmt: skip
