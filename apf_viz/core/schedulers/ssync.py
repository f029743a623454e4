"""SSYNC: each round a random non-empty subset."""

from __future__ import annotations

from typing import TYPE_CHECKING

from apf_viz.core.schedulers.base import StepRandom, candidates, starve_bound
from apf_viz.core.schedulers.rounds import RoundScheduler

if TYPE_CHECKING:
    from apf_viz.core.engine import Engine


class SsyncScheduler(RoundScheduler):
    """SSYNC: each round a random non-empty subset (each robot with probability 1/2), plus every robot
    that has waited past the fairness bound."""

    name = "ssync"
    label = "SSYNC"
    summary = "each round a random non-empty subset of the robots"

    def subset(self, engine: Engine, rng: StepRandom) -> tuple[int, ...]:
        """Each eligible robot with probability 1/2, plus any that waited past the fairness bound; one at
        random if that is none."""
        st = engine.state
        bound = starve_bound(engine)
        pool = candidates(engine).nonzero()[0].tolist()
        chosen = {r for r in pool if rng.random() < 0.5 or st.steps - st.last_act[r] >= bound}
        if not chosen:
            chosen = {pool[rng.randrange(len(pool))]}
        return tuple(sorted(chosen))
