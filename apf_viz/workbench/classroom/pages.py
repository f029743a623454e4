"""The pages connected to the class: each one's role, its state on the shared run (its selection, its
camera), its seat, and the run of its own it may try; which page holds the presenter's state, and who
besides the presenters may drive the shared run (the whole class, or the one page it was handed to)."""

from __future__ import annotations

import threading
from collections.abc import Hashable
from dataclasses import dataclass, field

from apf_viz.core.formats import InputError
from apf_viz.workbench.screen_state import BrowserState, Role
from apf_viz.workbench.session import Session


@dataclass(eq=False)
class Page:
    """One connected page. ``key`` is its connection (viser's client id in the server); ``seat`` the key
    its answers are held under, which a reload keeps (None: not issued yet)."""

    key: Hashable
    state: BrowserState
    seat: str | None = None
    own: Session | None = field(default=None, repr=False)  # its run of its own (Try it yourself)

    @property
    def role(self) -> Role:
        """Its role: a presenter page drives the shared run, a class page follows it."""
        return self.state.role


class Pages:
    """The connected pages, by key. The first presenter page to connect (or the first after it left)
    holds the shared run's presenter state, which scripts drive too and class pages may follow; every
    other page gets a state of its own."""

    def __init__(self, shared: Session) -> None:
        self.shared = shared
        self._pages: dict[Hashable, Page] = {}
        self._presenter_of: Hashable | None = None
        self._lock = threading.RLock()
        self.class_may_drive = False  # the presenter opened the shared run to the class pages
        self.driver: Hashable | None = None  # the one class page the presenter handed the run to
        shared.on_new_run(self._clear_selections)

    def join(self, key: Hashable, role: Role, seat: str | None = None) -> Page:
        """A page connects: a presenter page drives the shared run (the first holds the state the
        others may follow); a class page follows the lecture: it shows the presenter's selection until it
        selects a robot of its own, and drives only if the class may."""
        with self._lock:
            if role == "presenter" and self._presenter_of is None:
                self._presenter_of = key
                state = self.shared.presenter
            else:
                state = BrowserState(role=role, follow=role == "class")
            page = self._pages[key] = Page(key, state, seat)
            return page

    def promote(self, key: Hashable) -> Page:
        """A class page becomes a presenter page (it gave the presenter code): it holds the presenter's
        state if no page does, else it drives with a state of its own."""
        with self._lock:
            page = self._pages.get(key)
            if page is None:
                raise InputError("that page has left")
            if self._presenter_of is None or self._presenter_of == key:
                self._presenter_of = key
                page.state = self.shared.presenter
            else:
                page.state = BrowserState(role="presenter")
            return page

    def leave(self, key: Hashable) -> Page | None:
        """A page left: the run it was handed comes back to the presenter; the presenter's state waits
        for the next presenter page (a reload). The page, if it was here."""
        with self._lock:
            page = self._pages.pop(key, None)
            if key == self.driver:
                self.driver = None
            if key == self._presenter_of:
                self._presenter_of = None
            return page

    def get(self, key: Hashable | None) -> Page | None:
        """The page connected as ``key`` (None: no such page)."""
        with self._lock:
            return self._pages.get(key) if key is not None else None

    def all(self) -> list[Page]:
        """Every connected page, in the order they joined."""
        with self._lock:
            return list(self._pages.values())

    def state(self, key: Hashable | None) -> BrowserState:
        """That page's state on the shared run (the presenter's for None or a page not connected)."""
        page = self.get(key)
        return page.state if page is not None else self.shared.presenter

    def is_presenter(self, key: Hashable | None) -> bool:
        """Whether the page holds the presenter's state (the one the others follow)."""
        return self.state(key) is self.shared.presenter

    def may_drive(self, key: Hashable | None) -> bool:
        """Whether the page may change the shared run: a presenter page, any page while the presenter
        lets the class drive, or the one class page it handed the run to."""
        return (
            self.state(key).role == "presenter"
            or self.class_may_drive
            or (key is not None and key == self.driver)
        )

    def hand_run_to(self, page: Hashable | None, by: Hashable | None) -> str:
        """Let one class page (``page``) drive the shared run beside the presenter; None: take it back
        (a presenter page's choice only)."""
        if self.state(by).role != "presenter":
            raise InputError("only a presenter page hands the run to a class page")
        with self._lock:
            if page is not None and page not in self._pages:
                raise InputError("that page has left")
            self.driver = page
        return "the presenter drives the run alone" if page is None else "that page may drive the run too"

    def set_class_may_drive(self, on: bool, by: Hashable | None) -> str:
        """Open the shared run to the class pages, or close it (a presenter page's choice only)."""
        if self.state(by).role != "presenter":
            raise InputError("only a presenter page opens the run to the class")
        self.class_may_drive = bool(on)
        return "the class may drive the run" if on else "only the presenter drives the run"

    def _clear_selections(self) -> None:
        """A new shared run: every page's selection named a robot of the old one."""
        for page in self.all():
            page.state.selected = None
