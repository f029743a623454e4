"""Walks a session through a guided lecture (apf_viz/lecture.py): each stop loads its scenario (or goes on
with the run), runs to its condition, selects and compares what it names; `Next stop` and `Previous stop`
(PageDown / PageUp) move between stops, a previous stop replayed from the last scenario before it (runs
are reproducible: the same scenario, seed and adversary give the same events). Pure: no viser."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from apf_viz.lecture import MAX_EVENT, Lecture, Stop, Until
from apf_viz.ui.presenter import stage_of

if TYPE_CHECKING:  # the session holds its lecturer
    from apf_viz.ui.session import Session


@dataclass(frozen=True)
class Reached:
    """Where a stop left the run: whether its condition was met, at which event, and why not."""

    index: int
    met: bool
    event: int
    note: str = ""


class Lecturer:
    """One lecture on one session, and the stop it stands at (−1: before the first)."""

    def __init__(self, session: Session, lecture: Lecture, limit: int = MAX_EVENT) -> None:
        self.session, self.lecture, self.limit = session, lecture, limit
        self.position = -1
        self.reached: Reached | None = None

    @property
    def stop(self) -> Stop | None:
        return self.lecture.stops[self.position] if self.position >= 0 else None

    def next(self) -> Reached | None:
        """The next stop (None past the last)."""
        if self.position + 1 >= len(self.lecture.stops):
            return None
        return self.go(self.position + 1)

    def previous(self) -> Reached | None:
        """The stop before (None before the first), replayed from its scenario."""
        if self.position <= 0:
            return None
        return self.go(self.position - 1)

    def go(self, index: int) -> Reached:
        """Stand at stop ``index``: from the stop itself when it follows the current one, else replayed
        from the last stop at or before it that loads a scenario."""
        stops = self.lecture.stops
        first = index if index == self.position + 1 else max(i for i in range(index + 1) if stops[i].scenario)
        reached = Reached(index, True, self.session.engine.state.events)
        for i in range(first, index + 1):
            reached = self._apply(i, stops[i])
        self.position, self.reached = index, reached
        return reached

    def check(self) -> list[Reached]:
        """Every stop in order, as a lecture check the evening before."""
        self.position = -1
        return [self.go(i) for i in range(len(self.lecture.stops))]

    def _apply(self, index: int, stop: Stop) -> Reached:
        s = self.session
        if stop.scenario is not None:
            s.load_scenario(stop.scenario)
            s.compare_with(None)
        if stop.compare is not None:
            s.compare_with(stop.compare)
        met, note = (True, "") if stop.until is None else self._run_until(stop.until)
        if stop.select is not None:
            s.selected = stop.select if stop.select < s.engine.k else None
        return Reached(index, met, s.engine.state.events, note)

    def _run_until(self, until: Until) -> tuple[bool, str]:
        s = self.session
        e = s.engine
        while not self._met(until):
            if e.state.events >= self.limit:
                return False, f"not met within {self.limit:,} events"
            if not s.step():
                if until.outcome == "end":
                    return True, ""
                return False, f"the run ended ({e.outcome or 'no outcome'}) before {until.describe()}"
        return True, ""

    def _met(self, until: Until) -> bool:
        s, e = self.session, self.session.engine
        if until.event is not None:
            return e.state.events >= until.event
        if until.stage is not None:
            return until.stage in stage_of(s.run, s.screen)
        if until.outcome is not None:
            return e.outcome == until.outcome
        assert until.rule is not None
        if e.step_index == 0:
            return False
        last = e.history.steps[e.step_index - 1].events
        return any(ev.rule_id and until.rule in ev.rule_id.split("/") for ev in last if ev.phase == "compute")
