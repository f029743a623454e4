"""A run's changing state: each robot's phase in its cycle, and everything a step changes (copied whole
for the history's checkpoints). Its own module so that the history can keep states without importing
the engine that makes them."""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import IntEnum
from typing import Literal

import numpy as np

from apf_viz.core.algorithm import Decision
from apf_viz.core.view import Snapshot

Outcome = Literal["formed", "stuck", "limit", "collision"]


class Phase(IntEnum):
    """Where a robot is in its cycle; its next event is LOOK, COMPUTE or MOVE respectively."""

    IDLE = 0
    LOOKED = 1
    COMPUTED = 2


NEXT_EVENT = ("look", "compute", "move")  # indexed by Phase

# The phases as plain ints, for the hot paths (an IntEnum member's comparisons cost an attribute lookup
# and a call each; the engine compares phases on every event).
IDLE, LOOKED, COMPUTED = int(Phase.IDLE), int(Phase.LOOKED), int(Phase.COMPUTED)


@dataclass
class EngineState:
    """Everything that changes during a run; copied whole for checkpoints."""

    positions: np.ndarray  # shape (k, 2), int64, global frame
    lights: list[str]
    phase: np.ndarray  # shape (k,), int8 values of Phase
    snapshot: list[Snapshot | None]
    seen: list[tuple[int, ...] | None]  # who each robot saw at its Look (for traces and ghosts)
    look_step: np.ndarray  # shape (k,): step index of each robot's latest Look
    look_version: list[int]  # configuration version at each robot's latest Look
    pending: list[Decision | None]
    decided: list[Snapshot | None]  # the snapshot of each robot's latest Compute (kept after its Move)
    decided_seen: list[tuple[int, ...] | None]  # who that snapshot saw…
    decided_look: np.ndarray  # shape (k,): …and the step of its Look (what Why compares with now)
    last_act: np.ndarray  # shape (k,): step index of each robot's latest event (fairness)
    last_cycle_end: np.ndarray  # shape (k,): step index of each robot's latest Move (round-robin)
    steps: int = 0
    events: int = 0
    moves: int = 0
    cycles: int = 0
    round: int = 0
    outcome: Outcome | None = None
    lights_used: set[str] = field(default_factory=set)
    # Bumped on every move or light change: a cached view older than this may be out of date.
    version: int = 0
    starve_deadline: int = 0  # schedulers' cache: no robot is starved before this step…
    starve_key: int = -1  # …while Engine.eligible_gained is still this
    # Robot·steps passed over: at each step, the robots whose next cycle could change nothing (0 when
    # every activation is kept).
    skipped: int = 0

    def copy(self) -> EngineState:
        """A copy that shares nothing mutable with this one (a checkpoint, a branch): its arrays, lists and
        set copied."""
        return EngineState(
            positions=self.positions.copy(),
            lights=list(self.lights),
            phase=self.phase.copy(),
            snapshot=list(self.snapshot),
            seen=list(self.seen),
            look_step=self.look_step.copy(),
            look_version=list(self.look_version),
            pending=list(self.pending),
            decided=list(self.decided),
            decided_seen=list(self.decided_seen),
            decided_look=self.decided_look.copy(),
            last_act=self.last_act.copy(),
            last_cycle_end=self.last_cycle_end.copy(),
            steps=self.steps,
            events=self.events,
            moves=self.moves,
            cycles=self.cycles,
            round=self.round,
            outcome=self.outcome,
            lights_used=set(self.lights_used),
            version=self.version,
            starve_deadline=self.starve_deadline,
            starve_key=self.starve_key,
            skipped=self.skipped,
        )
