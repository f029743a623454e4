"""An ASYNC adversary that maximises staleness."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from apf_viz.core.engine_state import Phase
from apf_viz.core.history import StepRecord
from apf_viz.core.schedulers.base import NEVER, OneEventPerStep, StepRandom, candidates, most_starved

if TYPE_CHECKING:
    from apf_viz.core.engine import Engine


class StaleFirstScheduler(OneEventPerStep):
    """An ASYNC adversary that maximises staleness: everyone Looks and Computes as early as possible,
    and Moves are delayed until no other event is possible; then the robot holding the *oldest* snapshot
    moves. Every move is thus made on a snapshot taken before as many other moves as possible."""

    name = "stale-first"
    label = "stale-first"
    summary = "ASYNC delaying every Move: the oldest snapshot moves last"

    def choose(self, engine: Engine, rng: StepRandom) -> StepRecord:
        """A starved robot first; else a random eligible robot that has not Computed yet; else the robot whose
        pending Move rests on the oldest snapshot."""
        st = engine.state
        mask = candidates(engine)
        starved = most_starved(engine, mask)
        if starved is not None:
            return StepRecord((starved,))
        computed = st.phase == int(Phase.COMPUTED)
        early = (~computed & mask).nonzero()[0]
        if early.size:
            return StepRecord((int(early[rng.randrange(early.size)]),))
        # The oldest snapshot among the robots holding a pending Move. An idle robot's last Look is old
        # too, but activating it would start a cycle the skipping had passed over (its view answers
        # "same light, stay"): 40 such cycles per move at k = 40, none of which could change anything.
        return StepRecord((int(np.argmin(np.where(computed, st.look_step, NEVER))),))
