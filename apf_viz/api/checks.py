"""Every schedule of a small start from Python: :func:`check` runs ``apf-viz check``'s explorer and returns
a :class:`Verdict`, whose counterexample (if any) is a schedule to read and a run to replay."""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Literal

from apf_viz.algorithms import DEFAULT_ALGORITHM, algorithm_from_command_line
from apf_viz.api.inputs import Points, Start, start_of
from apf_viz.api.runs import Run, _seed, refuse_unsolvable
from apf_viz.core.algorithm import Algorithm
from apf_viz.core.files import write_atomic
from apf_viz.core.formats import InputError
from apf_viz.core.grid import Point
from apf_viz.explore.explorer import Result

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
    schedule: tuple[tuple[int, ...], ...]
    loop_start: int | None
    _robots: tuple[Point, ...]
    _pattern: tuple[Point, ...]
    _algorithm: Algorithm
    _scheduler: str
    _light_semantics: str

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
        return self.verdict not in ("verified", "budget")

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
) -> Verdict:
    """Explore every schedule of a small start (k ≤ 5), as ``apf-viz check`` does: ``flips="all"`` tries
    every assignment of the robots' y-axes, ``"file"`` the robots' own (or the random ones ``seed``
    draws). Stops at the first failure; the verdict, states and schedule are the command's.

    >>> v = check([(0, 0), (0, 1), (0, 2), (0, 4)], [(0, 1), (1, 1), (2, 1), (1, 0)],
    ...           algorithm="apf-opaque-grid-literal", flips="all")
    >>> v.verdict, len(v.schedule), v.replay().outcome
    ('collision', 41, 'collision')
    """
    from apf_viz.explore.check import all_flips
    from apf_viz.explore.check import check as explore

    start = start_of(robots, pattern)
    seed = _seed(seed)
    if scheduler not in ("async", "ssync", "fsync"):
        raise InputError(f"scheduler {scheduler!r}: check explores async, ssync or fsync")
    if flips not in ("all", "file"):
        raise InputError(f"flips {flips!r}: choose all or file")
    if not force:
        refuse_unsolvable(start)
    chosen, _ = algorithm_from_command_line(algorithm or DEFAULT_ALGORITHM)
    assignments = all_flips(len(start.robots)) if flips == "all" else [tuple(start.flips(seed))]
    result, y_up = explore(
        chosen,
        start.robots,
        start.pattern,
        assignments,
        scheduler,
        max_states,
        progress=False,
        light_semantics=light_semantics,
        reduction=reduction,
    )
    return Verdict.of(result, y_up, start, chosen, scheduler, light_semantics)
