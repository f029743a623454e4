"""The searched adversary from Python: :func:`adversary` runs ``apf-viz adversary``'s search (the built-in
schedulers' runs as the bar, then beams and variants of the costliest schedules) and returns a
:class:`Found`, whose schedule replays."""

from __future__ import annotations

import os
from dataclasses import dataclass, field

from apf_viz.algorithms import DEFAULT_ALGORITHM, get_algorithm
from apf_viz.api.checks import replay_schedule, write_schedule
from apf_viz.api.inputs import Points, Start, start_of
from apf_viz.api.progress_bars import ProgressBar
from apf_viz.api.runs import Run, _seed, refuse_unsolvable
from apf_viz.core.budget import paper_D
from apf_viz.core.formats import InputError


@dataclass(frozen=True)
class Found:
    """What the search found: :attr:`verdict` ``found`` with :attr:`count` (the most moves or events a
    schedule it searched forces), or the failure it met (``collision``, ``deadlock``; :attr:`count` None):
    then no worst exists, as ``apf-viz adversary`` says. :attr:`built_ins` is the bar (the built-in
    schedulers' most over seeds 0-19); :attr:`exact`: a beam never cut followed every path, so
    :attr:`count` is the exact worst. :attr:`schedule` (a schedule file's text, replayed to the same count
    or outcome before it is returned) is what :meth:`replay` plays."""

    maximize: str
    verdict: str
    count: int | None
    built_ins: int | None
    k: int
    D: int
    exact: bool
    evaluations: int
    built_in_runs: int
    seconds: float
    how: str
    y_up: tuple[bool, ...]
    schedule: str = field(repr=False)
    _start: Start = field(repr=False)
    _algorithm: str = field(repr=False)

    @property
    def per_kD(self) -> float | None:
        """The count as moves (events) per k·D, the paper's measure of cost."""
        return None if self.count is None else self.count / (self.k * self.D)

    @property
    def beats(self) -> bool:
        """The search found more than every built-in scheduler's run."""
        return (self.count or 0) > (self.built_ins or 0)

    def replay(self) -> Run:
        """The schedule found, played by the real engine: a :class:`Run` with :attr:`count` moves (events),
        or the failure met."""
        return replay_schedule(self.schedule, self._start, get_algorithm(self._algorithm), self.verdict)

    def save_schedule(self, path: str | os.PathLike[str]) -> None:
        """Write :attr:`schedule` (``apf-viz adversary --schedule-out``'s file)."""
        write_schedule(self.schedule, path, self.verdict)


def adversary(
    robots: Points,
    pattern: Points,
    *,
    maximize: str = "moves",
    budget: int = 2_000,
    seed: int = 1,
    algorithm: str | None = None,
    light_semantics: str = "compute",
    width: int | None = None,
    progress: bool = True,
    force: bool = False,
) -> Found:
    """Search for the schedule that forces the most ``maximize`` (moves or events), as ``apf-viz
    adversary`` does with the same options (the same seed, the same answer): ``budget`` schedules searched
    beside the built-in schedulers' runs, ``width`` the widest beam (0: none). ``seed`` seeds the search
    and, when the robots give no ``y_up``, their flips. A built-in algorithm only (a worker builds its own
    by name). Ctrl+C ends the search early with the best so far."""
    from apf_viz.explore.adversary import WIDTH, Problem, best_schedule_text, failure_schedule_text, search

    start = start_of(robots, pattern)
    seed = _seed(seed)
    name = algorithm or DEFAULT_ALGORITHM
    _refuse_options(maximize, budget, width, light_semantics, name)
    if not force:
        refuse_unsolvable(start)
    y_up = tuple(start.flips(seed))
    p = Problem(name, tuple(start.robots), tuple(start.pattern), y_up, maximize, light_semantics)  # type: ignore[arg-type]
    with ProgressBar("apf-viz adversary", budget, "schedules", progress) as bar:
        state = search(
            p, budget, seed, progress=lambda s: bar.to(s.evaluations, s.doing or f"best {s.best.value:,}"),
            width=WIDTH if width is None else width,
        )  # fmt: skip
    failure = state.failure
    k, d = len(start.robots), paper_D(start.robots, start.pattern)
    common = (k, d, state.exact, state.evaluations, state.bar_runs, state.seconds)
    if failure is not None:
        kind = {"stuck": "deadlock"}.get(failure.outcome or "", failure.outcome or "failure")
        text = failure_schedule_text(state)
        return Found(maximize, kind, None, None, *common, failure.source, y_up, text, start, name)
    text = best_schedule_text(state)
    best, bar_value = state.best.value or 0, state.bar.value or 0
    return Found(maximize, "found", best, bar_value, *common, state.best.source, y_up, text, start, name)


def _refuse_options(maximize: str, budget: int, width: int | None, light_semantics: str, name: str) -> None:
    """Every bad option in one line, before the search."""
    if maximize not in ("moves", "events"):
        raise InputError(f"maximize {maximize!r}: choose moves or events")
    if isinstance(budget, bool) or not isinstance(budget, int) or budget < 1:
        raise InputError(f"budget {budget!r}: schedules to search, 1 or more")
    if width is not None and (
        isinstance(width, bool) or not isinstance(width, int) or not 0 <= width <= 10**6
    ):
        raise InputError(f"width {width!r}: the widest beam, 0 to 1,000,000")
    if light_semantics not in ("compute", "lc-atomic"):
        raise InputError(f"light_semantics {light_semantics!r}: choose compute or lc-atomic")
    try:
        get_algorithm(name)
    except ValueError:
        raise InputError(f"algorithm {name!r}: the searched adversary takes a built-in algorithm") from None
