"""The play clock: how many steps a frame of Play takes, and which class pages' panels a frame brings up
to date while the run plays. Pure arithmetic on the time that passed: the server's render loop (ui/app.py)
reads it each frame, and tests drive it with made-up times."""

from __future__ import annotations

import itertools
import threading
from collections.abc import Hashable, Sequence
from typing import Any, TypeVar

__all__ = [
    "CLASS_HZ",
    "CLASS_REFRESHES",
    "FPS",
    "STEP_SHARE",
    "ClassTurns",
    "StepPacer",
    "play_budget",
]

FPS = 30
"""Frames a second, at most: the render loop's pace, whether playing or not."""
STEP_SHARE = 0.6
"""Of each frame, at most, this share goes to stepping the engine while playing."""
CLASS_HZ = 12.0
"""How often a class page's panel and selection are brought up to date while the run plays (the canvas
every page shares is drawn every frame, for all at once)."""
CLASS_REFRESHES = 360.0
"""How many class pages' panels and selections are brought up to date a second while the run plays, in
all: a class of up to 30 gets :data:`CLASS_HZ` each; a larger one shares this (60 pages: 6 a second
each), so the projector's frames do not pay for the size of the class."""

P = TypeVar("P", bound=Hashable)


def play_budget(budget: float, elapsed: float, speed: float) -> float:
    """The steps a frame of Play may take: what is left over, plus ``speed`` for the time since the last
    frame, capped at a frame's share plus one step in hand. The cap keeps a stalled frame from being
    made up in a burst; the step in hand keeps a frame a little shorter than 1/FPS, at a speed near FPS,
    from losing its fraction of a step (every other frame would step nothing: half the speed asked).

    Args:
        budget: the steps left over from the last frame (a fraction).
        elapsed: seconds since the last frame.
        speed: the steps a second asked for.
    """
    return min(budget + elapsed * speed, max(1.0, speed / FPS) + 1.0)


class StepPacer:
    """How many steps a call of Play may take in the time left of a frame's stepping share: a call is
    one step or a walk of many (core/fast_forward.py), whose cost per step ranges from microseconds (a
    same-sight walk) to a Look and a decision each (forced cycles in a crowd). The cost per step is the
    dearest of the recent calls', forgotten a fifth a call, so a call stops near the frame's deadline
    instead of running a whole frame's allowance past it."""

    def __init__(self) -> None:
        self.cost = 1e-4  # seconds a step, as last measured

    def allowance(self, budget: float, seconds_left: float) -> int:
        """Steps the next call may take: the budget's, within the seconds left at the measured cost."""
        return max(1, min(int(budget), int(seconds_left / self.cost)))

    def took(self, steps: int, seconds: float) -> None:
        """A call took ``steps`` in ``seconds``: the cost per step it is paced by from now on."""
        if steps:
            self.cost = max(seconds / steps, 0.8 * self.cost, 1e-7)


class ClassTurns:
    """The class pages are brought up to date in turn, whether the run plays or not: a change (a step, a
    frame of play, an answer, a click) makes every class page owed a refresh, and each frame refreshes
    the pages owed longest, :data:`CLASS_HZ` a second each, at most :data:`CLASS_REFRESHES` a second in
    all. A frame's work does not grow with the class: 200 pages idle beside a paused run once made every
    frame refresh all 200 panels (86 ms a frame, docs/PERFORMANCE.md); they now take 0.55 s to all be
    brought up to date, a few each frame, while the run plays or after it paused."""

    def __init__(self) -> None:
        self._owed: dict[Any, None] = {}  # pages owed a refresh (any hashable), longest owed first
        self._carry = 0.0  # refreshes owed to the rate, a fraction carried to the next frame
        self._lock = threading.Lock()  # a page hurries from viser's threads while a frame takes turns

    def due(self, class_pages: Sequence[P], changed: bool) -> list[P]:
        """The class pages to bring up to date in this frame (one frame of :data:`FPS`). ``changed``:
        something every page shows changed since the last frame (all of them are owed a refresh)."""
        with self._lock:
            return self._take(class_pages, changed)

    def _take(self, class_pages: Sequence[P], changed: bool) -> list[P]:
        here = set(class_pages)
        self._owed = {p: None for p in self._owed if p in here}
        if changed:
            for p in class_pages:
                self._owed.setdefault(p, None)  # a page owed already keeps its place in the line
        if not self._owed:
            self._carry = 0.0
            return []
        rate = min(len(class_pages) * CLASS_HZ, CLASS_REFRESHES)  # refreshes a second, the class in all
        self._carry = min(float(len(self._owed)), self._carry + rate / FPS)
        take = max(1, int(self._carry))  # at least one a frame: a class of two is not left waiting
        self._carry = max(0.0, self._carry - take)
        due: list[P] = list(itertools.islice(self._owed, take))
        for page in due:
            del self._owed[page]
        return due

    def hurry(self, page: Hashable) -> None:
        """``page`` did something itself (a tap, an answer): it is brought up to date first, in the
        next frame, not after the class."""
        with self._lock:
            self._owed = {page: None, **{p: None for p in self._owed if p != page}}

    @property
    def owing(self) -> bool:
        """Whether some class page is still owed a refresh (the next frame brings more up to date)."""
        return bool(self._owed)
