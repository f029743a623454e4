"""The record of a run: every step's choice and the events it produced, plus state checkpoints.

One record serves undo, timeline scrubbing, branching, exact replay, counterexamples and trace files.
Events are stored in the global frame with robots numbered in file order, exactly as traces write them.
"""

from __future__ import annotations

import bisect
from typing import TYPE_CHECKING, Literal, NamedTuple

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


class StepRecord(NamedTuple):
    """A scheduler's choice: which robots act together, and the synchronous round if any."""

    robots: tuple[int, ...]
    round: int | None = None


class RecordedStep(NamedTuple):
    record: StepRecord
    events: tuple[Event, ...]


class History:
    """Recorded steps (possibly beyond the engine's current position, after a seek) and checkpoints."""

    def __init__(self, initial: EngineState) -> None:
        self.steps: list[RecordedStep] = []
        self.generation = 0  # bumped when a branch drops recorded steps (caches of prefixes use it)
        self._checkpoint_steps: list[int] = [0]
        self._checkpoints: dict[int, EngineState] = {0: initial}

    @property
    def length(self) -> int:
        return len(self.steps)

    def record(self, position: int, record: StepRecord, events: list[Event]) -> None:
        """Store the step taken at ``position`` (0-based). A step equal to the recorded one keeps the
        future (a redo); a different one branches: the old future is dropped."""
        step = RecordedStep(record, tuple(events))
        if position == len(self.steps):
            self.steps.append(step)
            return
        if position < len(self.steps):
            if self.steps[position] == step:
                return
            del self.steps[position:]
            self.generation += 1
            self._drop_checkpoints_after(position)
        self.steps.append(step)

    def checkpoint(self, position: int, state: EngineState) -> None:
        if position not in self._checkpoints:
            bisect.insort(self._checkpoint_steps, position)
        self._checkpoints[position] = state

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
