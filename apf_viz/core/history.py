"""The record of a run: every step's choice and the events it produced, plus state checkpoints.

One record serves undo, timeline scrubbing, branching, exact replay, counterexamples and trace files.
Events are stored in the global frame with robots numbered in file order, exactly as traces write them.
"""

from __future__ import annotations

import bisect
from collections.abc import Iterator, Sequence
from typing import TYPE_CHECKING, Literal, NamedTuple, overload

import numpy as np

from apf_viz.core.grid import Direction, Point

if TYPE_CHECKING:
    from apf_viz.core.engine import EngineState

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


class StepRecord(NamedTuple):
    """A scheduler's choice: which robots act together, and the synchronous round if any."""

    robots: tuple[int, ...]
    round: int | None = None


class RecordedStep(NamedTuple):
    record: StepRecord
    events: tuple[Event, ...]


# A run records millions of steps. Stored as named tuples they stay tracked by the cyclic garbage
# collector forever, and its full passes over them cost more than the run itself; a plain tuple of
# atomic values (moves as their string) is untracked after its first collection. So steps are packed
# on record and unpacked on access.
_Packed = tuple  # (robots, round, events as plain tuples)


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


def _pack_seen(seen: tuple[int, ...]) -> bytes:
    """Who a Look saw, as a bit per robot: a large robot sees most of the others, and as a tuple of
    Python ints each Look cost about 30 bytes per robot seen (22 KB at k = 1,000, gigabytes per run)."""
    if not seen:
        return b""
    mask = np.zeros(seen[-1] + 1, dtype=bool)  # seen is sorted
    mask[np.fromiter(seen, dtype=np.intp, count=len(seen))] = True
    return np.packbits(mask).tobytes()


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


class Steps(Sequence[RecordedStep]):
    """The recorded steps as a read-only sequence (unpacked on access)."""

    def __init__(self, packed: list[_Packed]) -> None:
        self._packed = packed

    def __len__(self) -> int:
        return len(self._packed)

    @overload
    def __getitem__(self, i: int) -> RecordedStep: ...
    @overload
    def __getitem__(self, i: slice) -> list[RecordedStep]: ...
    def __getitem__(self, i: int | slice) -> RecordedStep | list[RecordedStep]:
        if isinstance(i, slice):
            return [_unpack(p) for p in self._packed[i]]
        return _unpack(self._packed[i])

    def __iter__(self) -> Iterator[RecordedStep]:
        return map(_unpack, self._packed)

    def record(self, i: int) -> StepRecord:
        """Step i's choice alone (what a replay needs), without unpacking its events."""
        robots, round, _ = self._packed[i]
        return StepRecord(robots, round)


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
        self._packed: list[_Packed] = []
        self.steps = Steps(self._packed)
        self.generation = 0  # bumped when a branch drops recorded steps (caches of prefixes use it)
        self.dropped: tuple[int, list[StepRecord]] | None = None  # the last branch's dropped steps
        self._checkpoint_steps: list[int] = [0]
        self._checkpoints: dict[int, EngineState] = {0: initial}

    @property
    def length(self) -> int:
        return len(self._packed)

    def record(self, position: int, record: StepRecord, events: list[Event]) -> None:
        """Store the step taken at ``position`` (0-based). A step equal to the recorded one keeps the
        future (a redo); a different one branches: the old future is dropped."""
        packed = self._packed
        step = _pack(record, events)
        if position == len(packed):  # the usual case: recording at the end
            packed.append(step)
            return
        if position < len(packed):
            if packed[position] == step:
                return
            self.dropped = (position, [StepRecord(p[0], p[1]) for p in packed[position:]])
            del packed[position:]
            self.generation += 1
            self._drop_checkpoints_after(position)
        packed.append(step)

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
