"""The frozen description of a run: everything Reset and every load rebuild it from."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace

from apf_viz.algorithms import Factory, get_algorithm
from apf_viz.core.engine import Engine, LightSemantics
from apf_viz.core.grid import Point


@dataclass(frozen=True)
class RunConfig:
    """Start, flips, pattern, algorithm, light semantics, scheduler and seed: a run is a function of
    these (and of the choices a person makes in Manual)."""

    robots: tuple[Point, ...]
    y_up: tuple[bool, ...]
    pattern: tuple[Point, ...]
    algorithm: str = "apf-opaque-grid"
    light_semantics: LightSemantics = "compute"
    scheduler: str = "async"
    seed: int = 1
    max_events: int = 5_000_000

    def engine(self, plugins: Mapping[str, Factory] | None = None) -> Engine:
        """A fresh engine at the start of this run."""
        return Engine(
            self.robots,
            self.pattern,
            get_algorithm(self.algorithm, plugins),
            y_up=self.y_up,
            light_semantics=self.light_semantics,
            max_events=self.max_events,
        )

    def but(self, **changes) -> RunConfig:
        """This configuration with some fields changed."""
        return replace(self, **changes)
