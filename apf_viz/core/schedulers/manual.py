"""Manual: the caller plays the adversary."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from apf_viz.core.history import StepRecord
from apf_viz.core.schedulers.base import Scheduler, StepRandom

if TYPE_CHECKING:
    from apf_viz.core.engine import Engine


@dataclass
class ManualScheduler:
    """The caller plays the adversary: :meth:`pick` queues robots; each step runs the next one's phase.
    With nothing queued it falls back to ``fallback`` (None: refuse)."""

    fallback: Scheduler | None = None
    # Class attributes, not fields (no annotation): the registry reads them off the class.
    name = "manual"
    label = "Manual"
    summary = "you pick the robot whose next phase runs"
    synchronous = False
    automatic = False
    forced_when_alone = False  # the caller picks

    def __post_init__(self) -> None:
        self._queue: list[int] = []

    def pick(self, robot: int) -> None:
        """Queue ``robot``: a later step runs its next phase."""
        self._queue.append(robot)

    def choose(self, engine: Engine, rng: StepRandom) -> StepRecord:
        """The next queued robot's phase; with none queued, the fallback's choice (a LookupError when there is
        none)."""
        if self._queue:
            return StepRecord((self._queue.pop(0),))
        if self.fallback is None:
            raise LookupError("manual scheduler: no robot picked")
        return self.fallback.choose(engine, rng)
