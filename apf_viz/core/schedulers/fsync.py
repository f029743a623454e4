"""FSYNC: every robot in every round."""

from __future__ import annotations

from typing import TYPE_CHECKING

from apf_viz.core.schedulers.base import StepRandom, candidates
from apf_viz.core.schedulers.rounds import RoundScheduler

if TYPE_CHECKING:
    from apf_viz.core.engine import Engine


class FsyncScheduler(RoundScheduler):
    """FSYNC: every robot in every round."""

    name = "fsync"
    label = "FSYNC"
    summary = "every robot in every round"

    def subset(self, engine: Engine, rng: StepRandom) -> tuple[int, ...]:
        """Every robot that can change something (all of them when none can)."""
        return tuple(candidates(engine).nonzero()[0].tolist())
