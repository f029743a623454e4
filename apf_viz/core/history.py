"""The record of a run: every step's choice and the events it produced, plus state checkpoints.

One record serves undo, timeline scrubbing, branching, exact replay, counterexamples and trace files.
Events are stored in the global frame with robots numbered in file order, exactly as traces write them.
"""

from __future__ import annotations

import bisect
from collections.abc import Iterator, Sequence
from typing import TYPE_CHECKING, Any, Literal, NamedTuple, overload

import numpy as np

from apf_viz.core.grid import Direction, Point

if TYPE_CHECKING:
    from apf_viz.core.engine_state import EngineState

EventPhase = Literal["look", "compute", "move"]


class Event(NamedTuple):
    """One Look, Compute or Move of one robot, with what it produced (global frame). A named tuple:
    millions are made per run, and a tuple is several times cheaper to build than a frozen dataclass."""

    robot: int
    phase: EventPhase
    sees: tuple[int, ...] | None = None  # look: indices of the robots seen
    light: str | None = None  # compute: the new light
    move: Direction | None = None  # compute: the pending move, global frame (None = stay)
    rule: str | None = None  # compute: the algorithm's rule that fired
    to: Point | None = None  # move: where the robot goes (its own point for a stay)
    round: int | None = None  # fsync/ssync round number
    collision: bool = False  # move: this move collided (the run stops, the move is not applied)
    rule_id: str | None = None  # compute: the stable id of the rule that fired (the algorithm's)


class Effect(NamedTuple):
    """What one event changed, without the robots a Look saw: replaying positions and lights over a long
    history (a timeline, a chart) needs nothing else, and a Look's robots, unpacked, are most of what a
    step costs to read (800 ints a Look at k = 1,000)."""

    robot: int
    phase: EventPhase
    light: str | None  # compute: the new light
    to: Point | None  # move: where the robot goes
    collision: bool

    @property
    def moved(self) -> bool:
        """A Move that happened (a collision stops the run instead): the robot now stands at ``to``."""
        return self.phase == "move" and not self.collision and self.to is not None


class StepRecord(NamedTuple):
    """A scheduler's choice: which robots act together, and the synchronous round if any."""

    robots: tuple[int, ...]
    round: int | None = None


class RecordedStep(NamedTuple):
    """One recorded step, unpacked: the scheduler's choice and the events it caused."""

    record: StepRecord
    events: tuple[Event, ...]


# A run records millions of steps. Stored as named tuples they stay tracked by the cyclic garbage
# collector forever, and its full passes over them cost more than the run itself; a plain tuple of
# atomic values (moves as their string) is untracked after its first collection. So steps are packed
# on record and unpacked on access.
_Packed = tuple[Any, ...]  # (robots, round, events as plain tuples)


def _pack(record: StepRecord, events: Sequence[Event]) -> _Packed:
    if len(events) == 1 and events[0][4] is None:  # the common case: one event, no move in it
        e = events[0]
        if e[2] is not None:  # a Look
            return (record[0], record[1], ((e[0], e[1], _pack_seen(e[2]), *e[3:]),))
        return (record[0], record[1], (tuple(e),))
    return (
        record[0],
        record[1],
        tuple(
            (
                e[0],
                e[1],
                _pack_seen(e[2]) if e[2] is not None else None,
                e[3],
                e.move.value if e.move is not None else None,
                *e[5:],
            )
            for e in events
        ),
    )


# One (seen, bits) pair whose bits were made more cheaply than from the tuple (views.py, from the array
# the view was built from): matched by the tuple's identity, so it can only ever answer for those ints.
_primed: tuple[tuple[int, ...] | None, bytes] = (None, b"")


def prime_seen(seen: tuple[int, ...], bits: bytes) -> None:
    """Tell :func:`_pack_seen` the bits of this very tuple (``bits_of_sorted`` of the same robots)."""
    global _primed
    _primed = (seen, bits)


def bits_of_sorted(robots: np.ndarray) -> bytes:
    """The robots (increasing indices, an array) as a bit per robot, as :func:`_pack_seen` packs them."""
    if not robots.shape[0]:
        return b""
    mask = np.zeros(int(robots[-1]) + 1, dtype=bool)
    mask[robots] = True
    return np.packbits(mask).tobytes()


def _pack_seen(seen: tuple[int, ...]) -> bytes:
    """Who a Look saw, as a bit per robot: a large robot sees most of the others, and as a tuple of
    Python ints each Look cost about 30 bytes per robot seen (22 KB at k = 1,000, gigabytes per run)."""
    primed = _primed
    if primed[0] is seen:
        return primed[1]
    return bits_of_sorted(np.fromiter(seen, dtype=np.intp, count=len(seen)))  # seen is sorted


def _unpack_seen(packed: bytes) -> tuple[int, ...]:
    return tuple(np.flatnonzero(np.unpackbits(np.frombuffer(packed, dtype=np.uint8))).tolist())


def _unpack(packed: _Packed) -> RecordedStep:
    robots, round, events = packed
    return RecordedStep(
        StepRecord(robots, round),
        tuple(
            Event(
                e[0],
                e[1],
                _unpack_seen(e[2]) if e[2] is not None else None,
                e[3],
                Direction(e[4]) if e[4] is not None else None,
                *e[5:],
            )
            for e in events
        ),
    )


_POSITIONS_KEPT = 64  # steps whose positions History.positions_after remembers (a robot's Looks, shown)
_ONE = StepRecord((0,))  # a placeholder choice: packing an event needs one


class Walk(NamedTuple):
    """A robot's fast-forwarded cycles (:mod:`apf_viz.core.fast_forward`), kept as one entry and expanded
    on access: every cycle's Look saw the same robots and its Compute made the same decision, and each
    Move is one lattice step further along ``delta``."""

    robot: int
    steps: int  # the steps it stands for (cycles × per_cycle, or a prefix of them after a branch)
    per_cycle: int  # 3, or 2 under lc-atomic (a Look and its Compute are one step)
    look: tuple[Any, ...]  # the packed Look event
    compute: tuple[Any, ...]  # the packed Compute event
    start: Point
    delta: Point  # global, one lattice step

    @classmethod
    def of(
        cls, robot: int, steps: int, per_cycle: int, look: Event, compute: Event, start: Point, delta: Point
    ) -> Walk:
        """A walk from the Look and Compute events every cycle of it repeats."""
        return cls(
            robot, steps, per_cycle, _pack(_ONE, [look])[2][0], _pack(_ONE, [compute])[2][0], start, delta
        )

    def step(self, i: int) -> _Packed:
        """Its i-th step (0-based), packed like a recorded one."""
        cycle, phase = divmod(i, self.per_cycle)
        robots = (self.robot,)
        if phase == self.per_cycle - 1:
            t = cycle + 1
            to = (self.start[0] + t * self.delta[0], self.start[1] + t * self.delta[1])
            return (robots, None, ((self.robot, "move", None, None, None, None, to, None, False, None),))
        if self.per_cycle == 2:
            return (robots, None, (self.look, self.compute))
        return (robots, None, (self.compute if phase else self.look,))


class Steps(Sequence[RecordedStep]):
    """The recorded steps as a read-only sequence (unpacked on access, walks expanded)."""

    def __init__(self, history: History) -> None:
        self._history = history

    def __len__(self) -> int:
        return self._history.length

    @overload
    def __getitem__(self, i: int) -> RecordedStep: ...
    @overload
    def __getitem__(self, i: slice) -> list[RecordedStep]: ...
    def __getitem__(self, i: int | slice) -> RecordedStep | list[RecordedStep]:
        history = self._history
        if isinstance(i, slice):
            if history._starts is None:
                return [_unpack(p) for p in history._packed[i]]
            return [_unpack(history.packed(j)) for j in range(history.length)[i]]
        if i < 0:
            i += history.length
        if not 0 <= i < history.length:
            raise IndexError(f"step {i} is outside the recorded history")
        return _unpack(history.packed(i))

    def between(self, start: int, stop: int) -> Iterator[RecordedStep]:
        """Steps ``start`` to ``stop`` − 1, unpacked one at a time: a long run's steps as one list would
        be gigabytes (half a million Looks of a 1,000-robot run, each seeing 800 robots)."""
        history = self._history
        for i in range(max(0, start), min(stop, history.length)):
            yield _unpack(history.packed(i))

    def __iter__(self) -> Iterator[RecordedStep]:
        for entry in self._history._packed:
            if type(entry) is Walk:
                for i in range(entry.steps):
                    yield _unpack(entry.step(i))
            else:
                yield _unpack(entry)

    def record(self, i: int) -> StepRecord:
        """Step i's choice alone (what a replay needs), without unpacking its events."""
        robots, round, _ = self._history.packed(i)
        return StepRecord(robots, round)


_REPEATS_KEPT = 1 << 16  # distinct Look and Compute steps remembered for sharing (then forgotten)
_THIN_EVERY = 64  # thin the checkpoints whenever their number is a multiple of this
_DENSE_AGE = 4096  # checkpoints younger than this many steps are all kept


def _keep(checkpoint: int, newest: int) -> bool:
    """Whether to keep a checkpoint, given the newest one: all within ``_DENSE_AGE`` steps (and any
    newer, after a seek back), else those at a multiple of a spacing that doubles as the age doubles
    (about age/64), so that 64 survive per doubling of age. A checkpoint dropped at one age would be
    dropped at every larger age too, so thinning never needs one it dropped."""
    age = newest - checkpoint
    if age < _DENSE_AGE or checkpoint == 0:
        return True
    spacing = 1 << ((age // _DENSE_AGE).bit_length() + 5)  # 64·2^⌊log2(age/_DENSE_AGE)⌋
    return checkpoint % spacing == 0


class History:
    """Recorded steps (possibly beyond the engine's current position, after a seek) and checkpoints."""

    def __init__(self, initial: EngineState) -> None:
        self._packed: list[_Packed | Walk] = []
        self._repeated: dict[_Packed, _Packed] = {}  # recent Look and Compute steps, each kept once
        self._length = 0  # steps recorded (a walk stands for many)
        # Each entry's first step, kept once a walk is recorded (until then entry i is step i).
        self._starts: list[int] | None = None
        self.steps = Steps(self)
        self.generation = 0  # bumped when a branch drops recorded steps (caches of prefixes use it)
        self.dropped: tuple[int, list[StepRecord]] | None = None  # the last branch's dropped steps
        self._checkpoint_steps: list[int] = [0]
        self._checkpoints: dict[int, EngineState] = {0: initial}
        self._positions_after: dict[tuple[int, int], np.ndarray] = {}  # (generation, n) → positions

    @property
    def length(self) -> int:
        """Steps recorded (a fast-forwarded walk counts as each of its steps)."""
        return self._length

    @property
    def entries(self) -> int:
        """Entries held in memory: a step each, a fast-forwarded walk one for all its steps."""
        return len(self._packed)

    def packed(self, i: int) -> _Packed:
        """Step i (0 ≤ i < length) as stored: packed, a walk's step expanded."""
        starts = self._starts
        if starts is None:
            return self._packed[i]
        e = bisect.bisect_right(starts, i) - 1
        entry = self._packed[e]
        return entry.step(i - starts[e]) if type(entry) is Walk else entry

    def effects(self, start: int, stop: int) -> Iterator[tuple[Effect, ...]]:
        """What each of steps ``start`` to ``stop`` − 1 changed, one step at a time (:class:`Effect`)."""
        for i in range(max(0, start), min(stop, self._length)):
            # A packed event: robot, phase, the Look's robots, light, move, rule, to, round, collision, ...
            yield tuple(Effect(e[0], e[1], e[3], e[6], e[8]) for e in self.packed(i)[2])

    def positions_after(self, n: int) -> np.ndarray:
        """Where every robot stood after the first ``n`` recorded steps, shape (k, 2), read-only: the
        latest checkpoint at or before ``n`` and the moves since (each step's effects, not its Looks).
        A snapshot's Look long ago is asked about at every frame its robot stays selected, so the
        answer is kept, per step, until a branch rewrites the history."""
        key = (self.generation, n)
        cached = self._positions_after.get(key)
        if cached is not None:
            return cached
        base, state = self.checkpoint_before(n)
        points = state.positions.copy()
        for effects in self.effects(base, n):
            for e in effects:
                if e.moved:
                    points[e.robot] = e.to
        points.setflags(write=False)
        if len(self._positions_after) >= _POSITIONS_KEPT:
            del self._positions_after[next(iter(self._positions_after))]  # the oldest asked
        self._positions_after[key] = points
        return points

    def record(self, position: int, record: StepRecord, events: list[Event]) -> None:
        """Store the step taken at ``position`` (0-based). A step equal to the recorded one keeps the
        future (a redo); a different one branches: the old future is dropped."""
        step = _pack(record, events)
        if step[2][-1][1] != "move":  # a Look or a Compute repeats, cycle after cycle: kept once
            step = self._repeated.setdefault(step, step)
            if len(self._repeated) > _REPEATS_KEPT:
                self._repeated = {}
        if position == self._length:  # the usual case: recording at the end
            self._append(step, 1)
            return
        if position < self._length:
            if self.packed(position) == step:
                return
            self._branch(position)
        self._append(step, 1)

    def record_walk(self, position: int, walk: Walk) -> None:
        """Store a fast-forwarded walk taken at ``position``, the end of the history."""
        if position != self._length:
            raise ValueError(
                f"a walk is recorded at the end of the history ({self._length}), not at {position}"
            )
        if self._starts is None:
            self._starts = list(range(len(self._packed)))
        self._append(walk, walk.steps)

    def _append(self, entry: _Packed | Walk, size: int) -> None:
        self._packed.append(entry)
        if self._starts is not None:
            self._starts.append(self._length)
        self._length += size

    def _branch(self, position: int) -> None:
        """Drop the recorded steps from ``position`` on (kept aside in ``dropped``)."""
        self.dropped = (position, [self.steps.record(i) for i in range(position, self._length)])
        starts = self._starts
        if starts is None:
            del self._packed[position:]
        else:
            e = bisect.bisect_right(starts, position) - 1
            entry = self._packed[e]
            keep = position - starts[e]
            if type(entry) is Walk and keep:
                self._packed[e] = entry._replace(steps=keep)
                e += 1
            del self._packed[e:]
            del starts[e:]
        self._length = position
        self.generation += 1
        self._drop_checkpoints_after(position)

    def checkpoint(self, position: int, state: EngineState) -> None:
        """Keep this state; then thin older checkpoints so that their spacing grows with their age.

        Every checkpoint holds the robots' snapshots: kept all, a long run's checkpoints outweigh the
        rest of it. Going back a little (``Back``, a scrub nearby) stays as fast as with all of them; a
        jump back by A steps replays at most about A/64 steps (see :func:`_keep`)."""
        if position not in self._checkpoints:
            bisect.insort(self._checkpoint_steps, position)
        self._checkpoints[position] = state
        if len(self._checkpoint_steps) % _THIN_EVERY == 0:
            kept = [p for p in self._checkpoint_steps if _keep(p, position)]
            for p in set(self._checkpoint_steps) - set(kept):
                del self._checkpoints[p]
            self._checkpoint_steps = kept

    def checkpoint_before(self, position: int) -> tuple[int, EngineState]:
        """The latest checkpoint at or before ``position``."""
        i = bisect.bisect_right(self._checkpoint_steps, position) - 1
        base = self._checkpoint_steps[i]
        return base, self._checkpoints[base]

    def events(self, upto: int | None = None) -> list[Event]:
        """All events of the first ``upto`` steps (all recorded steps if None), in order."""
        return [e for s in self.steps[:upto] for e in s.events]

    def _drop_checkpoints_after(self, position: int) -> None:
        keep = [p for p in self._checkpoint_steps if p <= position]
        for p in self._checkpoint_steps[len(keep) :]:
            del self._checkpoints[p]
        self._checkpoint_steps = keep
