"""What the view model reads of a run: a protocol, so that it depends on no controller (the
shared run's :class:`~apf_viz.workbench.run_controller.RunController` provides it; so
may a browser's own run)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Protocol

from apf_viz.core.engine import Engine
from apf_viz.workbench.branches import Branches
from apf_viz.workbench.move_series import MoveSeries
from apf_viz.workbench.run_config import RunConfig
from apf_viz.workbench.stage_log import StageLog


class RunSource(Protocol):
    """One run as the screen shows it: the engine, how it was configured, and how it is being played."""

    engine: Engine
    config: RunConfig
    following: bool  # a trace is followed step by step
    following_what: str  # "the trace", or what else is followed
    branches: Branches  # the lines of steps branches dropped

    def note_here(self) -> str:
        """The note a schedule's line wrote for the step just taken, if any."""
        ...

    @property
    def trace_options(self) -> Mapping[str, object]:
        """The followed trace's options (its verdict, its loop), empty when none is followed."""
        ...

    @property
    def playing(self) -> bool:
        """Whether Play is on."""
        ...

    @property
    def series(self) -> MoveSeries:
        """The run's (events, moves) after each recorded step."""
        ...

    @property
    def stages(self) -> StageLog:
        """Where each of the algorithm's stages began in this run."""
        ...

    @property
    def trace_position(self) -> tuple[int, int] | None:
        """(events so far, events in the trace) while a trace is followed, else None."""
        ...
