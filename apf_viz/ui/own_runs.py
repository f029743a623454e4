"""A class page's run of its own ("Try it yourself"), on the page: the classroom branches it and bounds
it (workbench/classroom/own_runs.py); here it is drawn on that page alone, in a scene of its own, and
played and drawn within a share of each frame.

A page's panel holds its door to the run it drives (workbench/classroom/page_run.py), so every command
the panel sends (Step, Back, Play, the scheduler, a click, Why) goes to its own run while it tries one.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable

from apf_viz.ui.browser_screen import BrowserScreen
from apf_viz.workbench.classroom import Classroom

OWN_DRAWS = 6.0
"""The most often an own run is drawn, a second: its page sees its run at six frames a second, and a
class of them costs the server a fifth of the messages that drawing every frame (30 a second) would."""
OWN_DRAW_SHARE = 0.1
"""The share of each frame that drawing the own runs may take; the pages not drawn are drawn next."""


class OwnRuns:
    """The app's side of own runs: a page branches one and goes back; each frame, every page attached
    to its own run is drawn from it alone, and those that play are played."""

    def __init__(
        self, classroom: Classroom, screens: Callable[[], list[BrowserScreen]], changed: Callable[[], None]
    ) -> None:
        self.classroom = classroom
        self._screens = screens
        self._changed = changed

    def try_alone(self, screen: BrowserScreen) -> str:
        """Branch a run of this page's own from the shared run as it is now, and show it there."""
        said = self.classroom.try_alone(screen.page.key)  # or why not, or that it runs one already
        if screen.own is not None or screen.page.own is None:
            return said
        screen.attach_own(screen.page.own)
        self.render(screen)
        screen.frame(screen.renderer)
        self._changed()
        return said

    def back(self, screen: BrowserScreen) -> str:
        """Drop this page's own run: it follows the shared run again."""
        said = self.classroom.back(screen.page.key)
        if screen.own is not None:
            screen.detach_own()
            screen.frame(screen.renderer)
            self._changed()
        return said

    def render(self, screen: BrowserScreen) -> None:
        """Draw a page's own run and its panel, in one message to that page."""
        own = screen.page.own
        assert own is not None and screen.own is not None
        screen.stale = False  # before it is drawn: a change made meanwhile is drawn in the next frame
        _, views = own.views({0: own.presenter})
        with screen.client.atomic():
            screen.draw_own(views[0])
            screen.panels.refresh(views[0])

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
            if screen.page.own is None:  # dropped meanwhile (the page left): nothing to draw
                continue
            try:
                self.render(screen)
            except RuntimeError:  # the browser left while its frame was drawn
                continue
            screen.drawn_at = now
        return left

    def play(self, screens: Iterable[BrowserScreen], frame_seconds: float, since: float) -> bool:
        """Plays the own runs that play, whose pages are then drawn anew; whether any plays."""
        played = {id(x) for x in self.classroom.play_own(frame_seconds, since)}
        for screen in screens:
            if id(screen.page) in played:
                screen.stale = True
        return bool(played)
