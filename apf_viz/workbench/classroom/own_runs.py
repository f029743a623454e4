"""A class page's run of its own ("Try it yourself"): branched from the shared run as it is now, driven
by that page alone, bounded, and dropped when the page goes back to the lecture or leaves.

The bounds keep a class from starving the projector: at most :data:`MAX_OWN_RUNS` at once, each at most
:data:`~apf_viz.workbench.session.branch.EXTRA_EVENTS` events past where it branched (its history's
memory), and their Play together at most :data:`OWN_SHARE` of a frame (:class:`OwnPlay`). A run of one's
own is a Session like the shared one; what only the shared run may do (files, lectures, the library on
the server's disk, the class's permission) is refused by the page's door to its run
(:class:`~apf_viz.workbench.classroom.page_run.PageRun`), not by the Session."""

from __future__ import annotations

import threading
import time
import weakref
from collections.abc import Callable, Iterable

from apf_viz.core.formats import InputError
from apf_viz.workbench.classroom.pages import Page
from apf_viz.workbench.session import Session
from apf_viz.workbench.session.branch import EXTRA_EVENTS as EXTRA_EVENTS
from apf_viz.workbench.session.branch import branch

__all__ = ["EXTRA_EVENTS", "MAX_OWN_RUNS", "OWN_SHARE", "OWN_SPEED", "OwnPlay", "OwnRuns"]

MAX_OWN_RUNS = 24
"""Runs of their own at once; the next page to ask is told to wait for one to end."""
OWN_SHARE = 0.15
"""The share of each frame that every own run's Play together may take; the shared run keeps the rest."""
OWN_SPEED = 60.0
"""The fastest an own run plays, in steps a second (the projector's run may go faster)."""


class OwnPlay:
    """Paces the own runs' Play: each at its own speed (at most :data:`OWN_SPEED`), all of them together
    within :data:`OWN_SHARE` of a frame; a run the frame has no time left for waits for the next."""

    def __init__(self) -> None:
        self._budget: weakref.WeakKeyDictionary[Session, float] = weakref.WeakKeyDictionary()

    def play(self, runs: Iterable[Session], frame_seconds: float, since: float) -> list[Session]:
        """Steps for ``since`` seconds of every playing run; the runs that were playing.

        Args:
            runs: the own runs (those not playing are passed over).
            frame_seconds: the length of a frame: the runs together take :data:`OWN_SHARE` of it.
            since: seconds since the last call, which each playing run is owed steps for.
        """
        playing = [run for run in runs if run.playing]
        deadline = time.perf_counter() + OWN_SHARE * frame_seconds
        for run in playing:
            budget = min(self._budget.get(run, 1.0) + min(OWN_SPEED, run.speed) * since, 4.0)
            if budget >= 1 and time.perf_counter() < deadline:
                run.play_steps(int(budget))
                budget -= int(budget)
            self._budget[run] = budget
        return playing


class OwnRuns:
    """The class pages' own runs: a page branches one and goes back; the bound on how many at once."""

    def __init__(self, shared: Session, pages: Callable[[], Iterable[Page]]) -> None:
        self.shared = shared
        self._pages = pages  # the connected pages, whose own runs count against the bound
        self._lock = threading.Lock()  # two pages asking at once cannot pass the bound together
        self.pacer = OwnPlay()

    def try_alone(self, page: Page) -> str:
        """Branch a run of ``page``'s own from the shared run as it is now. What the page is told."""
        if page.own is not None:
            return "this page already runs its own"
        if page.role != "class":
            raise InputError("Try it yourself is a class page's: a presenter page drives the shared run")
        with self._lock:  # counted under the lock: two pages asking at once cannot pass the bound together
            if sum(1 for x in self._pages() if x.own is not None) >= MAX_OWN_RUNS:
                raise InputError(
                    f"{MAX_OWN_RUNS} pages are trying runs of their own, the most this server allows: "
                    "try again when one goes back to the lecture"
                )
            page.own = branch(self.shared)
        return (
            f"your own run, from event {page.own.engine.state.events} of the lecture: Step, Play, Back and "
            "Manual act on it alone; Back to the lecture drops it"
        )

    @staticmethod
    def back(page: Page) -> str:
        """Drop ``page``'s own run: it follows the shared run again."""
        if page.own is None:
            return "this page follows the lecture"
        page.own = None
        return "back to the lecture"
