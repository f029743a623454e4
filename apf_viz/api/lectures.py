"""A lecture checked from Python: :func:`lecture_check` plays every stop of a guided lecture headless,
as ``apf-viz lecture check`` does, and returns what each stop reached."""

from __future__ import annotations

import os
from dataclasses import dataclass

from apf_viz.core.formats import InputError


@dataclass(frozen=True)
class StopChecked:
    """One stop: its number (1, 2, …) and title, what it runs to (:attr:`until`), whether that was met and
    its :attr:`claims` hold (:attr:`holds`), at which event, why not (:attr:`note`, :attr:`broken`), what
    the screen shows there in a claim's words, its question and the run's answer to it (at
    :attr:`answer_event`; None when it asks none)."""

    number: int
    title: str
    until: str
    met: bool
    event: int
    note: str
    claims: int
    broken: tuple[str, ...]
    shown: str
    asks: str | None
    answer: str | None
    answer_event: int | None

    @property
    def holds(self) -> bool:
        """Whether the stop was met and every claim at it holds."""
        return self.met and not self.broken


@dataclass(frozen=True)
class LectureChecked:
    """Every stop of a lecture, checked in order: :attr:`passed` when each holds."""

    title: str
    stops: tuple[StopChecked, ...]

    @property
    def passed(self) -> bool:
        """Whether every stop holds."""
        return all(stop.holds for stop in self.stops)

    def __repr__(self) -> str:
        held = sum(stop.holds for stop in self.stops)
        return f"<LectureChecked {self.title!r}: {held} of {len(self.stops)} stops hold>"


def lecture_check(lecture: str | os.PathLike[str]) -> LectureChecked:
    """Every stop of ``lecture`` (a lecture file, or a shipped lecture's name: ``algorithm-in-12-stops``,
    …) in order, headless: the stops ``apf-viz lecture check`` reports, with the same verdicts.

    >>> lecture_check("what-a-robot-cannot-see").passed
    True
    """
    from apf_viz.lecture import find_lecture
    from apf_viz.workbench.lecturer import Lecturer
    from apf_viz.workbench.session import Session

    if not isinstance(lecture, str | os.PathLike):
        raise InputError(f"lecture {lecture!r}: a lecture file's path, or a shipped lecture's name")
    found = find_lecture(os.fspath(lecture))
    blank = Session([(0, 0)], [(0, 0)])  # the first stop loads its scenario
    stops = []
    for reached in Lecturer(blank, found).check():
        stop = found.stops[reached.index]
        where = "its scenario's start" if stop.scenario else "where the stop before left the run"
        a = reached.answer if stop.ask is not None else None
        stops.append(
            StopChecked(
                reached.index + 1, stop.title, stop.until.describe() if stop.until else where, reached.met,
                reached.event, reached.note, stop.expect.count() if stop.expect else 0, reached.broken,
                reached.shown, stop.ask.words() if stop.ask is not None else None,
                a.words() if a is not None else None, a.event if a is not None else None,
            )
        )  # fmt: skip
    return LectureChecked(found.title, tuple(stops))
