"""The frozen description of a run: everything Reset and every load rebuild it from."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any

from apf_viz.algorithms import DEFAULT_ALGORITHM, Factory, get_algorithm
from apf_viz.core.budget import run_budget
from apf_viz.core.engine import Engine, LightSemantics
from apf_viz.core.grid import Point
from apf_viz.core.schedulers import DEFAULT_SCHEDULER


@dataclass(frozen=True)
class RunConfig:
    """Start, flips, pattern, algorithm, light semantics, scheduler and seed: a run is a function of
    these (and of the choices a person makes in Manual)."""

    robots: tuple[Point, ...]
    y_up: tuple[bool, ...]
    pattern: tuple[Point, ...]
    algorithm: str = DEFAULT_ALGORITHM
    light_semantics: LightSemantics = "compute"
    scheduler: str = DEFAULT_SCHEDULER
    seed: int = 1
    max_events: int = 5_000_000  # events a loaded trace may hold
    skip_noops: bool = True  # False: every no-op activation is kept (the All activations box)
    event_cap: int | None = None  # the run ends (``limit``) before passing this many events (an own run)

    def engine(self, plugins: Mapping[str, Factory] | None = None) -> Engine:
        """A fresh engine at the start of this run, stopped by the run's budget (core/budget.py)."""
        budget = run_budget(self.robots, self.pattern, self.skip_noops)
        return Engine(
            self.robots,
            self.pattern,
            get_algorithm(self.algorithm, plugins),
            y_up=self.y_up,
            light_semantics=self.light_semantics,
            max_events=budget.max_events
            if self.event_cap is None
            else min(budget.max_events, self.event_cap),
            max_moves=budget.max_moves,
            skip_noops=self.skip_noops,
            fast_forward=True,  # only Play at speed walks (RunController.play_steps); a step is one step
        )

    def but(self, **changes: Any) -> RunConfig:
        """This configuration with some fields changed."""
        return replace(self, **changes)
