"""What every scheduler shares: the protocol, the robots it may choose, the fairness bound, and the
per-step random generator.

A scheduler is stateless: :meth:`Scheduler.choose` reads the engine and a random generator seeded from
``(seed, step index)``. So a run is reproducible from its seed, and going back in time then stepping again
makes the same choices (pick a robot by hand, or change the seed, to branch).

Every scheduler is fair with an explicit bound: a robot that has not had an event for ``starve_bound``
steps (default ``4·k``, at least 16) is served before anyone else.

Schedulers choose among the robots whose next event can change something (``Engine.eligible``): an
idle robot whose view the algorithm answers with "same light, stay" is passed over until its view
changes (a legal ASYNC delay: its cycle would change nothing). With ``--all-activations`` every robot is
eligible, and the choices are exactly those of a scheduler that never skips.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Protocol, TypeVar

import numpy as np

from apf_viz.core.history import StepRecord

if TYPE_CHECKING:
    from apf_viz.core.engine import Engine

T = TypeVar("T")

new_step = tuple.__new__  # builds a StepRecord without the NamedTuple's Python-level __new__


class Scheduler(Protocol):
    """What chooses each step: the adversary of the paper, under its registry ``name``."""

    name: str
    # True when, with one eligible robot, it can only activate that robot, one event per step (and so a
    # lone robot's repeating cycles may be fast-forwarded: core/fast_forward.py).
    forced_when_alone: bool

    def choose(self, engine: Engine, rng: StepRandom) -> StepRecord:
        """The next step: robots to activate together (all in the same phase) and the round if any."""
        ...


class SchedulerKind(Protocol):
    """A scheduler's class as the registry reads it (``schedulers/__init__.py``): its class attributes,
    and calling it makes a scheduler."""

    name: str
    label: str  # in the UI's dropdown
    summary: str  # what it does, in a few words (--scheduler's help)
    synchronous: bool  # a round numbers its events: Looks, Computes, Moves of a group at once
    automatic: bool  # chooses by itself (Manual waits for the caller's picks)
    forced_when_alone: bool  # see Scheduler

    def __call__(self) -> Scheduler: ...


class OneEventPerStep:
    """What the ASYNC-like schedulers share: one robot, one event per step (no rounds); they choose by
    themselves; with one eligible robot they can only choose it (so fast-forward may walk it)."""

    synchronous = False
    automatic = True
    forced_when_alone = True


def starve_bound(engine: Engine) -> int:
    """The steps an eligible robot may wait before a fair scheduler must activate it."""
    return max(16, 4 * engine.k)


NEVER = np.iinfo(np.int64).max


def candidates(engine: Engine) -> np.ndarray:
    """The robots a scheduler may choose (whose next event can change something), as a bool mask; all of
    them if none can (the run is then over, and nobody asks)."""
    mask = engine.eligible()
    return mask if mask.any() else np.ones(engine.k, dtype=bool)


def most_starved(engine: Engine, mask: np.ndarray) -> int | None:
    """The eligible robot waiting longest, if it has waited past the fairness bound.

    ``last_act`` only grows, and until a robot becomes eligible (``Engine.eligible_gained``) eligible
    robots only leave the set, so no eligible robot can be starved before the least ``last_act`` among
    them + bound: that deadline is kept on the state. (Watched robots never act: a minimum over all
    robots would be far in the past, and every step would scan.)"""
    st = engine.state
    if st.steps < st.starve_deadline and st.starve_key == engine.eligible_gained:
        return None
    bound = starve_bound(engine)
    r = int(np.argmin(np.where(mask, st.last_act, NEVER)))  # ties: the lowest index
    if not mask[r]:
        return None
    if st.steps - st.last_act[r] >= bound:
        return r
    st.starve_deadline = int(st.last_act[r]) + bound
    st.starve_key = engine.eligible_gained
    return None


class StepRandom:
    """A small, fast generator (splitmix64) seeded from (seed, step): schedulers create one per step, and
    ``random.Random`` costs more to seed than a whole ASYNC step."""

    __slots__ = ("_state",)
    _MASK = (1 << 64) - 1

    def __init__(self, seed: int, step: int) -> None:
        self._state = (seed * 0x9E3779B97F4A7C15 + step * 0xBF58476D1CE4E5B9 + 1) & self._MASK

    def _next(self) -> int:
        self._state = (self._state + 0x9E3779B97F4A7C15) & self._MASK
        z = self._state
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & self._MASK
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & self._MASK
        return z ^ (z >> 31)

    def random(self) -> float:
        """A float in [0, 1), from the top 53 bits of the next draw."""
        return (self._next() >> 11) / float(1 << 53)

    def randrange(self, n: int) -> int:
        """An integer in [0, n)."""
        # _next inlined: ASYNC draws one number per event, and a method call costs as much as the mixing.
        mask = self._MASK
        z = self._state = (self._state + 0x9E3779B97F4A7C15) & mask
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & mask
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & mask
        return (z ^ (z >> 31)) % n  # bias below 2**-40 for any n we simulate

    def choice(self, seq: Sequence[T]) -> T:
        """An element of ``seq``, uniformly."""
        return seq[self.randrange(len(seq))]


def step_rng(seed: int, step: int) -> StepRandom:
    """The generator a scheduler uses at this step: a function of (seed, step) only."""
    return StepRandom(seed, step)
