"""The room at a glance, for the presenter: the class pages, anonymous ("laptop 7": numbered by seat, in
the order they first joined, so a reload keeps its number), which follow the lecture and which try a run
of their own, how far and with what outcome; one such run shown on the projector beside the shared
run, and taken down."""

from __future__ import annotations

import itertools
import weakref
from collections.abc import Callable, Hashable, Sequence
from dataclasses import dataclass, replace

from apf_viz.core.formats import InputError
from apf_viz.workbench.classroom.pages import Page
from apf_viz.workbench.seats import SEAT_PREFIX
from apf_viz.workbench.session import Session
from apf_viz.workbench.view_model import SessionView

__all__ = ["RoomList", "RoomPage"]


@dataclass(frozen=True)
class RoomPage:
    """One class page as the presenter sees it: no name, no address, only what it does with the run."""

    laptop: int
    own: bool  # trying a run of its own
    event: int  # where the run it shows stands
    outcome: str  # that run's outcome, or "running"
    drives: bool  # the presenter handed it the shared run
    shown: bool  # its run is on the projector beside the shared one
    answered: bool  # it answered the stop's question

    def words(self) -> str:
        """Its line in the presenter's Room folder ("laptop 7: its own run, event 40, running")."""
        state = self.outcome.upper() if self.outcome != "running" else "running"
        doing = f"its own run, event {self.event}, {state}" if self.own else "follows the lecture"
        marks = [
            m
            for m, on in (("drives", self.drives), ("beside", self.shown), ("answered", self.answered))
            if on
        ]
        return f"laptop {self.laptop}: {doing}" + (f" ({', '.join(marks)})" if marks else "")


class RoomList:
    """The class pages numbered as laptops, and the one whose own run is shown beside the shared run."""

    def __init__(self, shared: Session, pages: Callable[[], Sequence[Page]]) -> None:
        self.shared = shared
        self._pages = pages
        self._numbers: dict[str, int] = {}  # seat (or connection) -> laptop number
        self._keys: dict[Hashable, str] = {}  # a connected page's seat, read while it is connected
        self._shown: weakref.ref[Page] | None = None

    def laptop(self, page: Page) -> int:
        """Its number: its seat's (kept when it reloads), else its connection's, the lowest free."""
        seat = self._keys.get(page.key)
        if seat is None:
            seat = self._keys[page.key] = page.seat or f"page {page.key}"  # no seat yet: its connection
        number = self._numbers.get(seat)
        if number is None:
            used = set(self._numbers.values())
            number = self._numbers[seat] = next(n for n in itertools.count(1) if n not in used)
        return number

    def left(self, key: Hashable) -> None:
        """A page left: a seat keeps its number for when it comes back; a page without one frees it."""
        seat = self._keys.pop(key, None)
        if seat is not None and not seat.startswith(SEAT_PREFIX):
            self._numbers.pop(seat, None)

    def class_pages(self) -> list[Page]:
        """Every class page, by laptop number."""
        return sorted((x for x in self._pages() if x.role == "class"), key=self.laptop)

    def listing(self, driver: Hashable | None) -> list[RoomPage]:
        """Every class page as the presenter's list shows it, by laptop number."""
        shown = self.shown
        poll = self.shared.screen.poll
        out = []
        for page in self.class_pages():
            own = page.own
            out.append(
                RoomPage(
                    self.laptop(page),
                    own is not None,
                    own.engine.state.events if own is not None else 0,
                    (own.engine.outcome or "running") if own is not None else "running",
                    driver == page.key,
                    page is shown,
                    poll is not None and poll.given(page.seat) is not None,
                )
            )
        return out

    def page(self, laptop: int) -> Page:
        """The class page numbered ``laptop``; refused in one line if it is not in the room now."""
        for page in self.class_pages():
            if self.laptop(page) == laptop:
                return page
        raise InputError(f"laptop {laptop} is not in the room now")

    @property
    def shown(self) -> Page | None:
        """The page whose own run is beside the shared run (None once it went back or left)."""
        page = self._shown() if self._shown is not None else None
        if page is None or page.own is None or page not in self._pages():
            self._shown = None
            return None
        return page

    def show(self, laptop: int | None) -> str:
        """Put laptop ``laptop``'s own run beside the shared run on the projector (None: take it down)."""
        if laptop is None:
            self._shown = None
            return "the projector shows the lecture's run alone"
        page = self.page(laptop)
        if page.own is None:
            raise InputError(f"laptop {laptop} follows the lecture: it has no run of its own to show")
        if self.shared.screen.twin is not None:
            raise InputError("the projector compares two algorithms now: end Compare first")
        self._shown = weakref.ref(page)
        return f"laptop {laptop}'s run is beside the lecture's"

    def beside(self, run_view: SessionView) -> tuple[SessionView, str | None]:
        """The shared run's view with the shown laptop's run as the run beside it, and its title; the
        view as it is when none is shown (or Compare holds that place)."""
        page = self.shown
        own = page.own if page is not None else None
        if page is None or own is None or run_view.compare is not None:
            return run_view, None
        mine, _ = own.views({})
        state = mine.outcome.upper() if mine.outcome else "running"
        return replace(run_view, compare=mine), f"laptop {self.laptop(page)} · event {mine.event} · {state}"
