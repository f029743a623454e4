"""ASYNC: one Look, Compute or Move of a uniformly random eligible robot per step."""

from __future__ import annotations

from typing import TYPE_CHECKING

from apf_viz.core.history import StepRecord
from apf_viz.core.schedulers.base import OneEventPerStep, StepRandom, candidates, most_starved, new_step

if TYPE_CHECKING:
    from apf_viz.core.engine import Engine


class AsyncScheduler(OneEventPerStep):
    """ASYNC: one Look, Compute or Move of a uniformly random eligible robot per step."""

    name = "async"
    label = "ASYNC"
    summary = "one Look, Compute or Move of a random robot per step"

    def choose(self, engine: Engine, rng: StepRandom) -> StepRecord:
        """The starved robot if one has waited past the fairness bound, else a random eligible one: its next
        event."""
        mask = candidates(engine)
        r = most_starved(engine, mask)
        if r is None:  # with every robot eligible, the same draw as a scheduler that never skips
            pool = mask.nonzero()[0]
            r = int(pool[rng.randrange(pool.size)])
        return new_step(StepRecord, ((r,), None))
