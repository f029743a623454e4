"""The room at a glance, for the presenter: the class pages, anonymous ("laptop 7": numbered by seat, in
the order they first joined, so a reload keeps its number), which follow the lecture and which try a
run of their own, how far and with what outcome; one such run put on the projector beside the shared
run, and taken down; the shared run handed to one class page, and taken back."""

from __future__ import annotations

import itertools
import weakref
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import Any, Protocol

from apf_viz.core.formats import InputError
from apf_viz.workbench.screen_state import BrowserState
from apf_viz.workbench.session import Session
from apf_viz.workbench.view_model import SessionView


class BrowserScreen(Protocol):
    """What the room reads of a connected page (ui/browser_screen.py)."""

    @property
    def client(self) -> Any: ...  # its viser client

    @property
    def own(self) -> object | None: ...  # its own run's renderer, if it tries one

    @property
    def state(self) -> BrowserState: ...

    @property
    def session(self) -> Session: ...


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
        state = self.outcome.upper() if self.outcome != "running" else "running"
        doing = f"its own run, event {self.event}, {state}" if self.own else "follows the lecture"
        marks = [
            m
            for m, on in (("drives", self.drives), ("beside", self.shown), ("answered", self.answered))
            if on
        ]
        return f"laptop {self.laptop}: {doing}" + (f" ({', '.join(marks)})" if marks else "")


class Room:
    """The app's class pages, as the presenter's Room folder lists and acts on them."""

    def __init__(
        self,
        session: Session,
        screens: Callable[[], Sequence[BrowserScreen]],
        seat_of: Callable[[int], str | None],
    ) -> None:
        self.session = session
        self._screens = screens
        self._seat_of = seat_of
        self._numbers: dict[str, int] = {}  # seat -> laptop number
        self._keys: dict[int, str] = {}  # a connected page's seat, read while it is connected
        self._shown: weakref.ref[BrowserScreen] | None = None  # whose run is beside the shared one

    def laptop(self, screen: BrowserScreen) -> int:
        """Its number: its seat's (kept when it reloads), else its connection's, the lowest free."""
        cid = screen.client.client_id
        seat = self._keys.get(cid)
        if seat is None:
            seat = self._keys[cid] = self._seat_of(cid) or f"page {cid}"  # no seat yet: its connection
        number = self._numbers.get(seat)
        if number is None:
            used = set(self._numbers.values())
            number = self._numbers[seat] = next(n for n in itertools.count(1) if n not in used)
        return number

    def left(self, client_id: int) -> None:
        """A page left: a seat keeps its number for when it comes back; a page without one (one that went
        to its seat at once, or a viser that does not tell seats) frees its number."""
        key = self._keys.pop(client_id, None)
        if key is not None and not key.startswith("seat "):
            self._numbers.pop(key, None)

    def _class_pages(self) -> list[BrowserScreen]:
        pages = [x for x in self._screens() if x.state.role == "class"]
        return sorted(pages, key=self.laptop)

    def pages(self) -> list[RoomPage]:
        """Every class page, by laptop number."""
        shown = self.shown
        poll = self.session.screen.poll
        out = []
        for screen in self._class_pages():
            own = screen.own is not None
            engine = screen.session.engine  # a page that follows shows the lecture's run: not its own
            cid = screen.client.client_id
            out.append(
                RoomPage(
                    self.laptop(screen),
                    own,
                    engine.state.events if own else 0,
                    (engine.outcome or "running") if own else "running",
                    self.session.driver == cid,
                    screen is shown,
                    poll is not None and poll.given(self._seat_of(cid)) is not None,
                )
            )
        return out

    def _page(self, laptop: int) -> BrowserScreen:
        for screen in self._class_pages():
            if self.laptop(screen) == laptop:
                return screen
        raise InputError(f"laptop {laptop} is not in the room now")

    @property
    def shown(self) -> BrowserScreen | None:
        """The page whose own run is beside the shared run (None once it went back or left)."""
        screen = self._shown() if self._shown is not None else None
        if screen is None or screen.own is None or screen not in self._screens():
            self._shown = None
            return None
        return screen

    def show(self, laptop: int | None) -> str:
        """Put laptop ``laptop``'s own run beside the shared run on the projector (None: take it down)."""
        if laptop is None:
            self._shown = None
            return "the projector shows the lecture's run alone"
        screen = self._page(laptop)
        if screen.own is None:
            raise InputError(f"laptop {laptop} follows the lecture: it has no run of its own to show")
        if self.session.screen.twin is not None:
            raise InputError("the projector compares two algorithms now: end Compare first")
        self._shown = weakref.ref(screen)
        return f"laptop {laptop}'s run is beside the lecture's"

    def hand(self, laptop: int | None, presenter: object) -> str:
        """Hand the shared run to laptop ``laptop`` (None: take it back)."""
        page = None if laptop is None else self._page(laptop).client.client_id
        said = self.session.hand_run_to(page, presenter)
        return said if laptop is None else f"laptop {laptop} may drive the lecture's run too"

    def beside(self, run_view: SessionView) -> tuple[SessionView, str | None]:
        """The shared run's view with the shown laptop's run as the run beside it, and its title; the
        view as it is when none is shown (or Compare holds that place)."""
        screen = self.shown
        if screen is None or run_view.compare is not None:
            return run_view, None
        try:
            own, _ = screen.session.views([])
        except RuntimeError:
            return run_view, None
        state = own.outcome.upper() if own.outcome else "running"
        return replace(run_view, compare=own), f"laptop {self.laptop(screen)} · event {own.event} · {state}"
