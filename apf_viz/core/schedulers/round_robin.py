"""Sequential: robots in index order, each performing a whole cycle."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from apf_viz.core.history import StepRecord
from apf_viz.core.schedulers.base import NEVER, OneEventPerStep, StepRandom, candidates

if TYPE_CHECKING:
    from apf_viz.core.engine import Engine


class RoundRobinScheduler(OneEventPerStep):
    """Sequential: robots in index order, each performing a whole cycle (Look, Compute, Move)."""

    name = "round-robin"
    label = "round-robin"
    summary = "robots in turn, each a whole Look-Compute-Move cycle"

    def choose(self, engine: Engine, rng: StepRandom) -> StepRecord:
        """The robot in the middle of a cycle, if any (it finishes it); else the eligible robot whose last
        Move is oldest (ties: the lowest index)."""
        st = engine.state
        busy = st.phase.nonzero()[0]
        if busy.size:
            return StepRecord((int(busy[0]),))
        mask = candidates(engine)
        return StepRecord((int(np.argmin(np.where(mask, st.last_cycle_end, NEVER))),))
