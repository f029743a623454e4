"""The play clock: how many steps a frame of Play takes, and which class pages' panels a frame brings up
to date while the run plays. Pure arithmetic on the time that passed: the server's render loop (ui/app.py)
reads it each frame, and tests drive it with made-up times."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TypeVar

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

P = TypeVar("P")


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
    """While the run plays, the class pages are brought up to date in turn: :data:`CLASS_HZ` times a
    second each, at most :data:`CLASS_REFRESHES` in all (a share of them in each frame, so the work of a
    frame does not grow with the class). Not playing, every page in every frame."""

    def __init__(self) -> None:
        self._owed = 0.0  # refreshes owed, a fraction carried over
        self._turn = 0  # whose turn comes next

    def due(self, class_pages: Sequence[P], playing: bool, since: float) -> list[P]:
        """The class pages brought up to date in this frame, ``since`` seconds after the last."""
        if not playing:
            return list(class_pages)
        rate = min(len(class_pages) * CLASS_HZ, CLASS_REFRESHES)  # refreshes a second, the class in all
        self._owed = min(len(class_pages), self._owed + rate * min(0.25, since))
        take = int(self._owed)
        self._owed -= take
        start = self._turn % max(1, len(class_pages))
        self._turn = start + take
        return list((list(class_pages[start:]) + list(class_pages[:start]))[:take])
