"""The shape FSYNC and SSYNC share: rounds."""

from __future__ import annotations

from typing import TYPE_CHECKING

from apf_viz.core.engine_state import Phase
from apf_viz.core.history import StepRecord
from apf_viz.core.schedulers.base import StepRandom

if TYPE_CHECKING:
    from apf_viz.core.engine import Engine


class RoundScheduler:
    """Shared shape of FSYNC and SSYNC: a round is all chosen robots Looking, then Computing, then
    Moving simultaneously. The round in progress is read off the robots' phases. A subclass says which
    robots a new round takes (:meth:`subset`)."""

    name = ""
    synchronous = True
    automatic = True
    forced_when_alone = False  # a round numbers its events

    def choose(self, engine: Engine, rng: StepRandom) -> StepRecord:
        """The next phase of the round in progress (its Looked robots Compute, then its Computed robots
        Move), or a new round of :meth:`subset`."""
        st = engine.state
        for phase in (int(Phase.LOOKED), int(Phase.COMPUTED)):
            group = (st.phase == phase).nonzero()[0]
            if group.size:
                return StepRecord(tuple(group.tolist()), round=st.round)
        return StepRecord(self.subset(engine, rng), round=st.round + 1)

    def subset(self, engine: Engine, rng: StepRandom) -> tuple[int, ...]:
        """The robots a new round takes (the subclass says which)."""
        raise NotImplementedError
