"""The classroom: everything a class does around the shared run, with no viser. The pages and their
roles, the presenter's code and the seats, who drives (the run handed over and back), the answers to a
stop's question, the room's list, a laptop's run shown beside, the runs of one's own and their bounds,
and the play clock's turns. The server (ui/app.py) only turns viser's connections and events into calls
here and draws what it is told; tests drive a whole class through a lecture against it alone."""

from __future__ import annotations

from collections.abc import Hashable
from dataclasses import dataclass

from apf_viz.core.formats import InputError
from apf_viz.core.grid import Point
from apf_viz.workbench.classroom.own_runs import OwnRuns
from apf_viz.workbench.classroom.page_run import PageRun
from apf_viz.workbench.classroom.pages import Page, Pages
from apf_viz.workbench.classroom.play_clock import ClassTurns
from apf_viz.workbench.classroom.roles import Roles
from apf_viz.workbench.classroom.room_list import RoomList, RoomPage
from apf_viz.workbench.screen_state import BrowserState, Role
from apf_viz.workbench.seats import Seats
from apf_viz.workbench.session import Session
from apf_viz.workbench.view_model import SessionView

__all__ = ["Classroom", "Note"]


@dataclass(frozen=True)
class Note:
    """What one page is told after a command of its own: a notification's title and words."""

    title: str
    text: str
    error: bool = False


class Classroom:
    """The class around one shared :class:`Session`. Each page is known by a key (its connection)."""

    def __init__(self, shared: Session, roles: Roles | None = None, seats: Seats | None = None) -> None:
        self.shared = shared
        self.roles = roles or Roles()  # the presenter address's secret, and the code a person may type
        self.seats = seats or Seats()  # the class pages' seats, issued here
        self.pages = Pages(shared)
        self.room = RoomList(shared, self.pages.all)
        self.own_runs = OwnRuns(shared, self.pages.all)
        self.turns = ClassTurns()

    # ------------------------------------------------------------------ pages
    def join(self, key: Hashable, role: Role, seat: str | None = None) -> Page:
        """A page connects as ``role`` (the address it opened says which: :meth:`Roles.role_of`), with
        its seat (None: it has none yet, or is a presenter's)."""
        page = self.pages.join(key, role, seat)
        self._count_seats()
        return page

    def leave(self, key: Hashable) -> None:
        """A page left: its own run is dropped, the run it was handed comes back, its seat stays."""
        page = self.pages.leave(key)
        if page is not None:
            page.own = None
        self.room.left(key)
        self._count_seats()

    def _count_seats(self) -> None:
        """Tell the shared run which class pages' seats are here (a question's "3 of 5 answered")."""
        seats = frozenset(x.seat for x in self.pages.all() if x.role == "class" and x.seat is not None)
        self.shared.seat_the_room(seats)

    def page(self, key: Hashable | None) -> Page | None:
        """The page connected as ``key`` (None: no such page)."""
        return self.pages.get(key)

    def run_of(self, key: Hashable) -> PageRun:
        """The page's door to the run it drives: its own, or the shared one (a page not here: shared).
        The door holds nothing of its own: it reads the page's run each time it is used."""
        return PageRun(self.shared, self.pages.get(key) or Page(key, self.shared.presenter))

    def state(self, key: Hashable | None) -> BrowserState:
        """The page's state on the run it shows: on its own run, that run's presenter state."""
        page = self.pages.get(key)
        if page is not None and page.own is not None:
            return page.own.presenter
        return self.pages.state(key)

    def claim_presenter(self, key: Hashable, code: str) -> str:
        """A class page typed ``code``: if it is the presenter code, the page presents from now on."""
        ok = self.roles.claims(key, code)
        if ok is None:
            return "too many wrong codes from this page: open the presenter address instead"
        if not ok:
            return "that is not the presenter code (the terminal printed it)"
        page = self.pages.promote(key)
        page.own = None
        self._count_seats()
        return "this page presents: it drives the shared run"

    def is_presenter(self, key: Hashable | None) -> bool:
        """Whether the page holds the presenter's state (the one the class pages follow)."""
        return self.pages.is_presenter(key)

    def role(self, key: Hashable | None) -> Role:
        """The page's role ("presenter" for None or a page not here: scripts drive as the presenter)."""
        return self.pages.state(key).role

    def may_drive(self, key: Hashable | None) -> bool:
        """Whether the page may change the run it shows: its own always; the shared run as
        :meth:`Pages.may_drive` says."""
        page = self.pages.get(key)
        return (page is not None and page.own is not None) or self.pages.may_drive(key)

    @property
    def class_may_drive(self) -> bool:
        """Whether the presenter opened the shared run to every class page."""
        return self.pages.class_may_drive

    @property
    def driver(self) -> Hashable | None:
        """The one class page the presenter handed the shared run to (None: none)."""
        return self.pages.driver

    def set_class_may_drive(self, on: bool, by: Hashable | None) -> str:
        """Open the shared run to the class pages, or close it: page ``by``'s choice, if it presents."""
        return self.pages.set_class_may_drive(on, by)

    def set_follow(self, key: Hashable | None, follow: bool) -> None:
        """That page shows the presenter's selection (True) or its own (False)."""
        with self.shared.lock:
            self.state(key).follow = bool(follow)

    # ------------------------------------------------------------------ the room
    def laptop(self, key: Hashable) -> int | None:
        """A class page's number in the room's list (None: a presenter's page, or a page not here)."""
        page = self.pages.get(key)
        return self.room.laptop(page) if page is not None and page.role == "class" else None

    def listing(self) -> list[RoomPage]:
        """Every class page, by laptop number, as the presenter's Room folder lists it."""
        return self.room.listing(self.pages.driver)

    def hand(self, laptop: int | None, by: Hashable | None) -> str:
        """Hand the shared run to laptop ``laptop`` (None: take it back): a presenter page's choice."""
        page = None if laptop is None else self.room.page(laptop).key
        said = self.pages.hand_run_to(page, by)
        return said if laptop is None else f"laptop {laptop} may drive the lecture's run too"

    def show(self, laptop: int | None) -> str:
        """Laptop ``laptop``'s own run beside the shared run on the projector (None: take it down)."""
        return self.room.show(laptop)

    def beside(self, run_view: SessionView) -> tuple[SessionView, str | None]:
        """The shared run's view with the shown laptop's run beside it, and that run's title."""
        return self.room.beside(run_view)

    # ------------------------------------------------------------------ runs of one's own
    def own_pages(self) -> list[Page]:
        """The pages trying a run of their own now."""
        return [x for x in self.pages.all() if x.own is not None]

    def try_alone(self, key: Hashable) -> str:
        """Branch a run of the page's own from the shared run as it is now."""
        page = self._page(key)
        return self.own_runs.try_alone(page)

    def back(self, key: Hashable) -> str:
        """Drop the page's own run: it follows the shared run again."""
        return self.own_runs.back(self._page(key))

    def play_own(self, frame_seconds: float, since: float) -> list[Page]:
        """Plays the own runs that play, within their share of a frame; the pages whose run played."""
        pages = self.own_pages()
        played = self.own_runs.pacer.play([x.own for x in pages if x.own is not None], frame_seconds, since)
        return [x for x in pages if x.own in played]

    def _page(self, key: Hashable) -> Page:
        page = self.pages.get(key)
        if page is None:
            raise InputError("that page has left")
        return page

    # ------------------------------------------------------------------ questions and clicks
    def answer(self, key: Hashable, choice: str) -> str:
        """The page answers the stop's question (again: its answer changes); for that page only."""
        page = self.pages.get(key)
        return self.shared.answer_question(page.seat if page is not None else None, choice)

    def click(self, key: Hashable | None, cell: Point) -> list[Note]:
        """A page clicked ``cell``: a class page following the lecture answers a question a click
        answers (which robot, which cell); then the click goes to the run the page shows (a selection,
        a Manual step, a drawing's cell). What the page is told."""
        page = self.pages.get(key)
        notes: list[Note] = []
        if page is not None and page.own is None and page.role == "class":
            try:
                said = self.shared.answer_by_click(page.seat, cell)
                if said:
                    notes.append(Note("Question", said))
            except InputError as err:
                notes.append(Note("Question", str(err), error=True))
        run = page.own if page is not None and page.own is not None else self.shared
        try:
            run.click(cell, self.state(key), self.may_drive(key))
        except InputError as err:
            notes.append(Note("Click refused", str(err), error=True))
        return notes

    # ------------------------------------------------------------------ the play clock
    def due(self, keys: list[Hashable], changed: bool) -> list[Hashable]:
        """Of the pages following the shared run (``keys``), those brought up to date in this frame:
        every presenter page; the class pages in turn (:class:`ClassTurns`). ``changed``: the frame
        shows a change (every class page is owed a refresh)."""
        roles = {k: self.role(k) for k in keys}
        turn = set(self.turns.due([k for k in keys if roles[k] == "class"], changed))
        return [k for k in keys if roles[k] != "class" or k in turn]
