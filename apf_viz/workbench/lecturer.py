"""Walks a session through a guided lecture (apf_viz/lecture.py): each stop loads its scenario (or goes on
with the run), runs to its condition, selects and compares what it names; `Next stop` and `Previous stop`
(PageDown / PageUp) move between stops, a previous stop replayed from the last scenario before it (runs
are reproducible: the same scenario, seed and adversary give the same events). Pure: no viser."""

from __future__ import annotations

import re
from collections import Counter
from dataclasses import dataclass
from typing import Protocol

from apf_viz.core.engine import Engine
from apf_viz.lecture import (
    MAX_EVENT,
    Expect,
    Lecture,
    Stop,
    Until,
    claimed_lights,
    contradiction,
    frameless_coordinates,
    panel_words,
)
from apf_viz.workbench.colour_words import untrue_colours
from apf_viz.workbench.question import Answer, answer
from apf_viz.workbench.screen_state import RunMark, SharedScreen
from apf_viz.workbench.view_model import SessionView, stage_of
from apf_viz.workbench.view_model.run_source import RunSource


class Lectern(Protocol):
    """What a lecture drives: a session (workbench/session/), which holds its lecturer."""

    selected: int | None

    @property
    def engine(self) -> Engine:
        """The run's engine, where the run stands now."""
        ...

    @property
    def run(self) -> RunSource:
        """The run as the screen shows it: its engine, configuration and branches."""
        ...

    @property
    def screen(self) -> SharedScreen:
        """What every page shows alike besides the run (a stop's marks, Compare, the poll)."""
        ...

    def load_scenario(self, name: str) -> str:
        """Replace the run with a Demo scenario by its name; returns what it shows."""
        ...

    def compare_with(self, algorithm: str | None) -> None:
        """Compare the run with ``algorithm`` beside it; None stops comparing."""
        ...

    def step(self) -> bool:
        """One step chosen by the scheduler; False if nothing ran."""
        ...

    def seek(self, step: float) -> None:
        """Go to that step of the history."""
        ...

    def view(self) -> SessionView:
        """What the presenter's page shows."""
        ...


@dataclass(frozen=True)
class Reached:
    """Where a stop left the run: whether its condition was met, at which event, and why not."""

    index: int
    met: bool
    event: int
    note: str = ""
    broken: tuple[str, ...] = ()  # the stop's claims that do not hold there, each in words
    shown: str = ""  # what the screen shows there, in the words a claim uses (to write claims from)
    answer: Answer | None = None  # the answer the run gives to the stop's question

    @property
    def holds(self) -> bool:
        """Reached, and everything it says is true on screen."""
        return self.met and not self.broken


class Lecturer:
    """One lecture on one session, and the stop it stands at (−1: before the first)."""

    def __init__(self, session: Lectern, lecture: Lecture, limit: int = MAX_EVENT) -> None:
        self.session, self.lecture, self.limit = session, lecture, limit
        self.position = -1
        self.reached: Reached | None = None
        # Where the current stop left the run: its engine, history generation and step. A stop's words
        # hold there only, so the next stop starts from there, not from wherever Play went meanwhile.
        self.mark: RunMark | None = None

    @property
    def stop(self) -> Stop | None:
        """The stop the lecture stands at (None before the first)."""
        return self.lecture.stops[self.position] if self.position >= 0 else None

    def next(self) -> Reached | None:
        """The next stop (None past the last)."""
        if self.position + 1 >= len(self.lecture.stops):
            return None
        return self.go(self.position + 1)

    def previous(self) -> Reached | None:
        """The stop before (None before the first), replayed from its scenario; off the current stop
        (played or stepped away from it), back to the current stop itself."""
        if self.position >= 0 and not (self.mark is not None and self.mark.holds(self.session.engine)):
            if self._back_at_stop() and self.reached is not None:
                return self.reached
            return self.go(self.position)
        if self.position <= 0:
            return None
        return self.go(self.position - 1)

    def go(self, index: int) -> Reached:
        """Stand at stop ``index``: from the stop itself when it follows the current one, else replayed
        from the last stop at or before it that loads a scenario."""
        stops = self.lecture.stops
        follows = index == self.position + 1 and self._back_at_stop()
        first = index if follows else max(i for i in range(index + 1) if stops[i].scenario)
        reached = Reached(index, True, self.session.engine.state.events)
        for i in range(first, index + 1):
            reached = self._apply(i, stops[i])
        self.position, self.reached = index, reached
        self.mark = RunMark.of(self.session.engine)
        return reached

    def _back_at_stop(self) -> bool:
        """Put the run back where the current stop left it, if it moved on (Play, Step, Back) along the
        same history; False if it cannot (another run loaded, a branch dropped those steps): the stop is
        then replayed from its scenario. Either way the next stop is reached as PageDown alone reaches it."""
        if self.position < 0:
            return True  # the first stop loads its scenario
        e = self.session.engine
        if self.mark is None or not self.mark.on_history(e):
            return False
        if e.step_index != self.mark.step:
            self.session.seek(self.mark.step)
        return True

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
        view = s.view()
        broken = broken_claims(stop, view)
        answered = answer(s, stop.ask) if stop.ask is not None and met else None
        if isinstance(answered, str):
            broken += (f"its question “{stop.ask.words()}” has no answer: {answered}",)  # type: ignore[union-attr]
            answered = None
        return Reached(index, met, s.engine.state.events, note, broken, shown(view), answered)

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


def broken_claims(stop: Stop, view: SessionView) -> tuple[str, ...]:
    """What ``stop`` says that the screen does not show when it is reached: its ``expect`` claims, and
    words that name a panel (presentation mode hides the panel, so the room cannot see it)."""
    out = [
        f"its words name “{words}”, which presentation mode hides"
        for text in (stop.title, stop.say)
        if (words := panel_words(text))
    ]
    if pair := frameless_coordinates(stop.say):
        out.append(f"its words give {pair} in no named frame (the leader's, a robot's own, on the grid)")
    if said := contradiction(f"{stop.title}. {stop.say}", view.stage_line):
        out.append(said)
    lit = Counter(r.light for r in view.robots)
    for light in claimed_lights(f"{stop.title}. {stop.say}", view.legend):
        if not lit[light]:
            showing = ", ".join(f"{n} {other}" for other, n in sorted(lit.items()))
            out.append(f"its words say a robot is lit {light}; none is at this stop (they show {showing})")
    out += untrue_colours(f"{stop.title}. {stop.say}", view)
    if stop.select is not None and stop.select >= len(view.robots):
        k = len(view.robots)
        out.append(f"selects robot {stop.select}, but the run has {k} robots (0–{k - 1})")
    return tuple(out + (_broken_expectations(stop.expect, view) if stop.expect else []))


def shown(view: SessionView) -> str:
    """The stage, the lights and the marks on screen, in the words ``expect`` takes."""
    lights = ", ".join(f"{light} {n}" for light, n in sorted(Counter(r.light for r in view.robots).items()))
    marks = ", ".join(f"“{m.label}”" for m in view.overlays.marks) or "none"
    said = f"stage “{view.stage_line}”; lights {lights}; marks {marks}; state {view.outcome or 'running'}"
    if view.selected is not None:
        hidden = len(view.hidden)
        said += f"; robot {view.selected} sees {len(view.robots) - 1 - hidden}, {hidden} hidden"
    return said


def _broken_expectations(expect: Expect, view: SessionView) -> list[str]:
    out = []
    shown = Counter(r.light for r in view.robots)
    for light, n in (expect.lights or {}).items():
        if shown[light] != n:
            out.append(f"expects {n} robot(s) lit {light}, the screen shows {shown[light]}")
    state = view.outcome or "running"
    if expect.state is not None and state != expect.state:
        out.append(f"expects the run {expect.state}, it is {state}")
    if expect.compare_state is not None:
        other = "not compared" if view.compare is None else view.compare.outcome or "running"
        if other != expect.compare_state:
            out.append(f"expects the run beside it {expect.compare_state}, it is {other}")
    if expect.stage is not None and expect.stage not in view.stage_line:
        out.append(f"expects the stage “{expect.stage}”, the stage line says “{view.stage_line}”")
    labels = [m.label for m in view.overlays.marks]
    for label in expect.drawn or []:
        if not any(re.search(rf"(?<!\w){re.escape(label)}(?!\w)", x) for x in labels):
            marks = ", ".join(f"“{x}”" for x in labels) or "none"
            out.append(f"expects “{label}” drawn, the marks are {marks}")
    if expect.sees is not None or expect.hidden is not None:
        out += _sight(expect, view)
    if expect.stale is not None and bool(view.stale_holders) != expect.stale:
        holders = ", ".join(map(str, view.stale_holders)) or "none"
        out.append(f"expects {'a' if expect.stale else 'no'} stale snapshot, robots holding one: {holders}")
    return out


def _sight(expect: Expect, view: SessionView) -> list[str]:
    if view.selected is None:
        return ["expects what the selected robot sees, but no robot is selected"]
    hidden = len(view.hidden)
    sees = len(view.robots) - 1 - hidden
    out = []
    if expect.sees is not None and sees != expect.sees:
        out.append(f"expects robot {view.selected} to see {expect.sees} robot(s), it sees {sees}")
    if expect.hidden is not None and hidden != expect.hidden:
        out.append(f"expects {expect.hidden} robot(s) hidden from robot {view.selected}, {hidden} are")
    return out
