"""The adversaries: who acts next. They choose among robots; the engine decides what an activation does.

One file per scheduler, and one registration: :data:`REGISTRY` below. The CLI's choices, the UI's
dropdown, the view model's sentences and the tests all read it (docs/ARCHITECTURE.md, "Extending").
"""

from __future__ import annotations

from apf_viz.core.schedulers.asynchronous import AsyncScheduler
from apf_viz.core.schedulers.base import (
    Scheduler,
    SchedulerKind,
    StepRandom,
    candidates,
    starve_bound,
    step_rng,
)
from apf_viz.core.schedulers.fsync import FsyncScheduler
from apf_viz.core.schedulers.manual import ManualScheduler
from apf_viz.core.schedulers.round_robin import RoundRobinScheduler
from apf_viz.core.schedulers.ssync import SsyncScheduler
from apf_viz.core.schedulers.stale_first import StaleFirstScheduler

REGISTRY: tuple[SchedulerKind, ...] = (
    FsyncScheduler,
    SsyncScheduler,
    AsyncScheduler,
    RoundRobinScheduler,
    StaleFirstScheduler,
    ManualScheduler,
)
"""Every scheduler, in the order the CLI and the UI list them."""

SCHEDULERS: tuple[str, ...] = tuple(kind.name for kind in REGISTRY)
AUTOMATIC: tuple[str, ...] = tuple(kind.name for kind in REGISTRY if kind.automatic)
"""The schedulers that choose by themselves: those a batch run (run, sweep, the light lab) may use."""
BY_HAND: tuple[str, ...] = tuple(kind.name for kind in REGISTRY if not kind.automatic)
"""The schedulers the person drives (a click or Step picks the robot): Manual."""
DEFAULT_SCHEDULER = "async"
"""The adversary of a run nobody chose one for (the command line's default, a new session's)."""
SYNCHRONOUS: tuple[str, ...] = tuple(kind.name for kind in REGISTRY if kind.synchronous)
"""The schedulers whose rounds number their events (a round is a group's Looks, Computes, Moves)."""

__all__ = [
    "AUTOMATIC",
    "BY_HAND",
    "DEFAULT_SCHEDULER",
    "REGISTRY",
    "SCHEDULERS",
    "SYNCHRONOUS",
    "AsyncScheduler",
    "FsyncScheduler",
    "ManualScheduler",
    "RoundRobinScheduler",
    "Scheduler",
    "SchedulerKind",
    "SsyncScheduler",
    "StaleFirstScheduler",
    "StepRandom",
    "candidates",
    "kind_of",
    "make_scheduler",
    "ordered",
    "starve_bound",
    "step_rng",
]


def kind_of(name: str) -> SchedulerKind:
    """A scheduler's class by its CLI name; a one-line error naming the choices otherwise."""
    for kind in REGISTRY:
        if kind.name == name:
            return kind
    raise ValueError(f"unknown scheduler {name!r}; choose one of {', '.join(SCHEDULERS)}")


def make_scheduler(name: str) -> Scheduler:
    """A scheduler by its CLI name (see :data:`SCHEDULERS`)."""
    return kind_of(name)()


def ordered(preferred: tuple[str, ...], names: tuple[str, ...] = AUTOMATIC) -> tuple[str, ...]:
    """``names`` with ``preferred`` first in its order (a campaign whose cases are numbered keeps them),
    then any scheduler registered since, in the registry's order."""
    return tuple(n for n in preferred if n in names) + tuple(n for n in names if n not in preferred)
