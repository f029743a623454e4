"""The adversaries: who acts next. They choose among robots; the engine decides what an activation does.

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

from dataclasses import dataclass
from typing import TYPE_CHECKING, Protocol

import numpy as np

from apf_viz.core.engine import Phase
from apf_viz.core.history import StepRecord

if TYPE_CHECKING:
    from apf_viz.core.engine import Engine

_new = tuple.__new__  # builds a StepRecord without the NamedTuple's Python-level __new__

SCHEDULERS = ("fsync", "ssync", "async", "round-robin", "stale-first", "manual")


class Scheduler(Protocol):
    name: str
    # True when, with one eligible robot, it can only activate that robot, one event per step (and so a
    # lone robot's repeating cycles may be fast-forwarded: core/fast_forward.py).
    forced_when_alone: bool

    def choose(self, engine: Engine, rng: StepRandom) -> StepRecord:
        """The next step: robots to activate together (all in the same phase) and the round if any."""
        ...


def starve_bound(engine: Engine) -> int:
    return max(16, 4 * engine.k)


_NEVER = np.iinfo(np.int64).max


def candidates(engine: Engine) -> np.ndarray:
    """The robots a scheduler may choose (whose next event can change something), as a bool mask; all of
    them if none can (the run is then over, and nobody asks)."""
    mask = engine.eligible()
    return mask if mask.any() else np.ones(engine.k, dtype=bool)


def _most_starved(engine: Engine, mask: np.ndarray) -> int | None:
    """The eligible robot waiting longest, if it has waited past the fairness bound.

    ``last_act`` only grows, and until a robot becomes eligible (``Engine.eligible_gained``) eligible
    robots only leave the set, so no eligible robot can be starved before the least ``last_act`` among
    them + bound: that deadline is kept on the state. (Watched robots never act: a minimum over all
    robots would be far in the past, and every step would scan.)"""
    st = engine.state
    if st.steps < st.starve_deadline and st.starve_key == engine.eligible_gained:
        return None
    bound = starve_bound(engine)
    r = int(np.argmin(np.where(mask, st.last_act, _NEVER)))  # ties: the lowest index
    if not mask[r]:
        return None
    if st.steps - st.last_act[r] >= bound:
        return r
    st.starve_deadline = int(st.last_act[r]) + bound
    st.starve_key = engine.eligible_gained
    return None


class AsyncScheduler:
    """ASYNC: one Look, Compute or Move of a uniformly random eligible robot per step."""

    name = "async"
    forced_when_alone = True

    def choose(self, engine: Engine, rng: StepRandom) -> StepRecord:
        mask = candidates(engine)
        r = _most_starved(engine, mask)
        if r is None:  # with every robot eligible, the same draw as a scheduler that never skips
            pool = mask.nonzero()[0]
            r = int(pool[rng.randrange(pool.size)])
        return _new(StepRecord, ((r,), None))


class RoundRobinScheduler:
    """Sequential: robots in index order, each performing a whole cycle (Look, Compute, Move)."""

    name = "round-robin"
    forced_when_alone = True

    def choose(self, engine: Engine, rng: StepRandom) -> StepRecord:
        st = engine.state
        busy = st.phase.nonzero()[0]
        if busy.size:
            return StepRecord((int(busy[0]),))
        mask = candidates(engine)
        return StepRecord((int(np.argmin(np.where(mask, st.last_cycle_end, _NEVER))),))


class StaleFirstScheduler:
    """An ASYNC adversary that maximises staleness: everyone Looks and Computes as early as possible,
    and Moves are delayed until no other event is possible; then the robot holding the *oldest* snapshot
    moves. Every move is thus made on a snapshot taken before as many other moves as possible."""

    name = "stale-first"
    forced_when_alone = True

    def choose(self, engine: Engine, rng: StepRandom) -> StepRecord:
        st = engine.state
        mask = candidates(engine)
        starved = _most_starved(engine, mask)
        if starved is not None:
            return StepRecord((starved,))
        computed = st.phase == int(Phase.COMPUTED)
        early = (~computed & mask).nonzero()[0]
        if early.size:
            return StepRecord((int(early[rng.randrange(early.size)]),))
        # The oldest snapshot among the robots holding a pending Move. An idle robot's last Look is old
        # too, but activating it would start a cycle the skipping had passed over (its view answers
        # "same light, stay"): 40 such cycles per move at k = 40, none of which could change anything.
        return StepRecord((int(np.argmin(np.where(computed, st.look_step, _NEVER))),))


class _RoundScheduler:
    """Shared shape of FSYNC and SSYNC: a round is all chosen robots Looking, then Computing, then
    Moving simultaneously. The round in progress is read off the robots' phases."""

    name = ""
    forced_when_alone = False  # a round numbers its events

    def choose(self, engine: Engine, rng: StepRandom) -> StepRecord:
        st = engine.state
        for phase in (int(Phase.LOOKED), int(Phase.COMPUTED)):
            group = (st.phase == phase).nonzero()[0]
            if group.size:
                return StepRecord(tuple(group.tolist()), round=st.round)
        return StepRecord(self.subset(engine, rng), round=st.round + 1)

    def subset(self, engine: Engine, rng: StepRandom) -> tuple[int, ...]:
        raise NotImplementedError


class FsyncScheduler(_RoundScheduler):
    """FSYNC: every robot in every round."""

    name = "fsync"

    def subset(self, engine: Engine, rng: StepRandom) -> tuple[int, ...]:
        return tuple(candidates(engine).nonzero()[0].tolist())


class SsyncScheduler(_RoundScheduler):
    """SSYNC: each round a random non-empty subset (each robot with probability 1/2), plus every robot
    that has waited past the fairness bound."""

    name = "ssync"

    def subset(self, engine: Engine, rng: StepRandom) -> tuple[int, ...]:
        st = engine.state
        bound = starve_bound(engine)
        pool = candidates(engine).nonzero()[0].tolist()
        chosen = {r for r in pool if rng.random() < 0.5 or st.steps - st.last_act[r] >= bound}
        if not chosen:
            chosen = {pool[rng.randrange(len(pool))]}
        return tuple(sorted(chosen))


@dataclass
class ManualScheduler:
    """The caller plays the adversary: :meth:`pick` queues robots; each step runs the next one's phase.
    With nothing queued it falls back to ``fallback`` (None: refuse)."""

    fallback: Scheduler | None = None
    name: str = "manual"
    forced_when_alone = False  # the caller picks

    def __post_init__(self) -> None:
        self._queue: list[int] = []

    def pick(self, robot: int) -> None:
        self._queue.append(robot)

    def choose(self, engine: Engine, rng: StepRandom) -> StepRecord:
        if self._queue:
            return StepRecord((self._queue.pop(0),))
        if self.fallback is None:
            raise LookupError("manual scheduler: no robot picked")
        return self.fallback.choose(engine, rng)


def make_scheduler(name: str) -> Scheduler:
    """A scheduler by its CLI name (see :data:`SCHEDULERS`)."""
    table: dict[str, type] = {
        "fsync": FsyncScheduler,
        "ssync": SsyncScheduler,
        "async": AsyncScheduler,
        "round-robin": RoundRobinScheduler,
        "stale-first": StaleFirstScheduler,
        "manual": ManualScheduler,
    }
    try:
        return table[name]()
    except KeyError:
        raise ValueError(f"unknown scheduler {name!r}; choose one of {', '.join(SCHEDULERS)}") from None


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
        return (self._next() >> 11) / float(1 << 53)

    def randrange(self, n: int) -> int:
        # _next inlined: ASYNC draws one number per event, and a method call costs as much as the mixing.
        mask = self._MASK
        z = self._state = (self._state + 0x9E3779B97F4A7C15) & mask
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & mask
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & mask
        return (z ^ (z >> 31)) % n  # bias below 2**-40 for any n we simulate

    def choice(self, seq):
        return seq[self.randrange(len(seq))]


def step_rng(seed: int, step: int) -> StepRandom:
    """The generator a scheduler uses at this step: a function of (seed, step) only."""
    return StepRandom(seed, step)
