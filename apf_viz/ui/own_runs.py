"""A class page's run of its own ("Try it yourself"): branched from the shared run as it is now, driven
and drawn on that page alone, bounded, and dropped when the page goes back to the lecture or leaves.

A page is *attached* to a run: the shared one, or its own. Its panel holds an
:class:`~apf_viz.ui.attachment.Attachment`, so
every command the panel sends (Step, Back, Play, the scheduler, a click, Why) goes to the run it is
attached to, and nothing of an own run reaches the shared one. The bounds keep a class from starving the
projector: at most :data:`MAX_OWN_RUNS` at once, each at most :data:`EXTRA_EVENTS` events past where it
branched (its history's memory), and their Play together at most :data:`OWN_SHARE` of a frame.
"""

from __future__ import annotations

import threading
import time
import weakref
from collections.abc import Callable, Iterable

from apf_viz.core.formats import InputError
from apf_viz.ui.browser_screen import BrowserScreen
from apf_viz.workbench.session import Session
from apf_viz.workbench.session.branch import EXTRA_EVENTS as EXTRA_EVENTS
from apf_viz.workbench.session.branch import branch as branch

MAX_OWN_RUNS = 24
"""Runs of their own at once; the next page to ask is told to wait for one to end."""
"""How far an own run may go past where it branched (a few MB of history); it then ends ("budget")."""
OWN_SHARE = 0.15
"""The share of each frame that every own run's Play together may take; the shared run keeps the rest."""
OWN_SPEED = 60.0
"""The fastest an own run plays, in steps a second (the projector's run may go faster)."""
OWN_DRAWS = 6.0
"""The most often an own run is drawn, a second: its page sees its run at six frames a second, and a
class of them costs the server a fifth of the messages that drawing every frame (30 a second) would."""
OWN_DRAW_SHARE = 0.1
"""The share of each frame that drawing the own runs may take; the pages not drawn are drawn next."""


class OwnPlay:
    """Paces the own runs' Play: each at its own speed (at most :data:`OWN_SPEED`), all of them together
    within :data:`OWN_SHARE` of a frame; a run the frame has no time left for waits for the next."""

    def __init__(self) -> None:
        self._budget: weakref.WeakKeyDictionary[Session, float] = weakref.WeakKeyDictionary()

    def play(self, runs: Iterable[Session], frame_seconds: float, since: float) -> list[Session]:
        """Steps for ``since`` seconds of every playing run; the runs that were playing."""
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
    """The app's side of own runs: a page branches one and goes back; each frame, every page attached
    to its own run is drawn from it alone, and those that play are played (:class:`OwnPlay`)."""

    def __init__(
        self, shared: Session, screens: Callable[[], list[BrowserScreen]], changed: Callable[[], None]
    ) -> None:
        self.shared = shared
        self._screens = screens
        self._changed = changed
        self._lock = threading.Lock()  # two pages asking at once cannot pass the bound together
        self.pacer = OwnPlay()

    def attached(self) -> list[BrowserScreen]:
        return [x for x in self._screens() if x.own is not None]

    def try_alone(self, screen: BrowserScreen) -> str:
        """Branch a run of this page's own from the shared run as it is now."""
        if screen.own is not None:
            return "this page already runs its own"
        if screen.state.role != "class":
            raise InputError("Try it yourself is a class page's: a presenter page drives the shared run")
        with self._lock:
            if len(self.attached()) >= MAX_OWN_RUNS:
                raise InputError(
                    f"{MAX_OWN_RUNS} pages are trying runs of their own, the most this server allows: "
                    "try again when one goes back to the lecture"
                )
            own = branch(self.shared)
            screen.attach_own(own)
        self.render(screen)
        screen.frame(screen.renderer)
        self._changed()
        return (
            f"your own run, from event {own.engine.state.events} of the lecture: Step, Play, Back and "
            "Manual act on it alone; Back to the lecture drops it"
        )

    def back(self, screen: BrowserScreen) -> str:
        """Drop this page's own run: it follows the shared run again."""
        if screen.own is None:
            return "this page follows the lecture"
        screen.detach_own()
        screen.frame(screen.renderer)
        self._changed()
        return "back to the lecture"

    def render(self, screen: BrowserScreen) -> None:
        """Draw a page's own run and its panel, in one message to that page."""
        assert screen.own is not None
        screen.stale = False  # before it is drawn: a change made meanwhile is drawn in the next frame
        cid = screen.client.client_id
        _, views = screen.session.views([cid])
        with screen.client.atomic():
            screen.draw_own(views[cid])
            screen.panels.refresh(views[cid])

    def draw(self, screens: Iterable[BrowserScreen], frame_seconds: float) -> bool:
        """Draw the pages whose own run changed: each at most :data:`OWN_DRAWS` times a second, those
        waiting longest first, within :data:`OWN_DRAW_SHARE` of the frame; whether any is left to draw."""
        now = time.perf_counter()
        end = now + OWN_DRAW_SHARE * frame_seconds
        waiting = sorted((x for x in screens if x.own is not None and x.stale), key=lambda x: x.drawn_at)
        left = False
        for screen in waiting:
            if now - screen.drawn_at < 1.0 / OWN_DRAWS or time.perf_counter() > end:
                left = True
                continue
            try:
                self.render(screen)
            except RuntimeError:  # the browser left while its frame was drawn
                continue
            screen.drawn_at = now
        return left

    def play(self, frame_seconds: float, since: float) -> bool:
        """Plays the own runs that play, which are then drawn anew; whether any plays."""
        attached = self.attached()
        playing = self.pacer.play([x.session for x in attached], frame_seconds, since)
        for screen in attached:
            if screen.session in playing:
                screen.stale = True
        return bool(playing)
