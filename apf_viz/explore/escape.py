"""An escape shown, not assumed: the explorer's ``escape`` says only that a robot left the box it explores
(docs/VERIFICATION.md); whether the walk ends is another question. A robot may leave the box and stop at
its corner a few cells beyond, and then the run forms.

Evidence that the walk does not end: the counterexample, replayed event for event, then continued by a
fair scheduler until the continuation's event cap, while the robot that left keeps walking away (farther
from the box than where the trace left it, by at least :data:`FARTHER`). Without such a continuation the
verdict is "left the explored box", not a failure, and the light lab looks at its next start.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass

from apf_viz.core.algorithm import Algorithm
from apf_viz.core.formats import TraceHeader
from apf_viz.core.grid import Point, as_point
from apf_viz.core.history import Event
from apf_viz.core.run import advance, engine_for_trace, replay
from apf_viz.core.schedulers import make_scheduler

FAIR = ("async", "stale-first", "round-robin")
"""The continuations: ASYNC schedulers that activate every robot infinitely often (a trace stops mid-cycle,
where a synchronous round cannot start)."""
SEEDS = (1, 2, 3, 4)
CONTINUED_EVENTS = 6_000
"""Events each continuation may add: far more than the few dozen a formation from the explorer's small
starts takes (a walk the engine fast-forwards counts every event it stands for)."""
FARTHER = 100
"""Cells farther from the box than where the trace left the robot: a walk that stops at a corner a few
cells beyond the box never gets there."""


@dataclass(frozen=True)
class Continuation:
    """One fair continuation of a counterexample: how it ended and how far the robot is from the box."""

    scheduler: str
    seed: int
    outcome: str  # formed, stuck, collision, or limit (its events ran out)
    distance: int  # Chebyshev cells from the box around start ∪ pattern, at the end
    walked_from: int  # the same where the trace ended

    @property
    def escapes(self) -> bool:
        return self.outcome == "limit" and self.distance >= self.walked_from + FARTHER

    def describe(self, robot: int) -> str:
        if self.escapes:
            return (
                f"continued fairly ({self.scheduler}, seed {self.seed}), robot {robot} is still walking "
                f"away: {self.distance:,} cells from the box after {CONTINUED_EVENTS:,} more events"
            )
        return f"continued fairly ({self.scheduler}, seed {self.seed}) the run ends {self.outcome}"


def distance_from_box(p: Point, points: Sequence[Point]) -> int:
    """Chebyshev distance of ``p`` from the bounding box of ``points`` (0 inside)."""
    xs, ys = [q[0] for q in points], [q[1] for q in points]
    dx = max(min(xs) - p[0], 0, p[0] - max(xs))
    dy = max(min(ys) - p[1], 0, p[1] - max(ys))
    return max(dx, dy)


def continuations(
    header: TraceHeader, events: Sequence[Event], algorithm: Algorithm, robot: int
) -> Iterator[Continuation]:
    """The trace replayed, then continued by each fair scheduler and seed in turn."""
    box = [as_point(p) for p in header.robots] + [as_point(p) for p in header.pattern]
    for scheduler in FAIR:
        for seed in SEEDS:
            engine = engine_for_trace(header, algorithm, max_events=len(events) + CONTINUED_EVENTS)
            replay(engine, events)
            start = distance_from_box(engine.current_points()[robot], box)
            if not engine.finished:
                advance(engine, make_scheduler(scheduler), seed)
            end = distance_from_box(engine.current_points()[robot], box)
            yield Continuation(scheduler, seed, engine.outcome or "running", end, start)


def escape_evidence(
    header: TraceHeader, events: Sequence[Event], algorithm: Algorithm, robot: int
) -> Continuation | None:
    """The first fair continuation in which ``robot`` keeps walking away to the cap, or None: then the
    trace shows a robot that left the explored box, not a walk without end."""
    for continuation in continuations(header, events, algorithm, robot):
        if continuation.escapes:
            return continuation
    return None


def escaping_robot(detail: str) -> int:
    """The robot an explorer's escape names ("escape: robot 3 left the box at (9, 0)")."""
    return int(detail.removeprefix("escape: ").removeprefix("robot ").split()[0])
