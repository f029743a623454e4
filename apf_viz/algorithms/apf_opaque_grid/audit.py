"""Auditing runs of the paper's algorithm: the invariants the issue and the paper promise, checked from
outside the engine's own verdict (used by the end-to-end tests and the soak)."""

from __future__ import annotations

import random
from collections.abc import Callable
from dataclasses import dataclass, field

from apf_viz.core.engine import Engine
from apf_viz.core.grid import Point
from apf_viz.core.run import collector_paused
from apf_viz.core.schedulers import Scheduler, make_scheduler, step_rng
from apf_viz.core.symmetry import unsolvable_axis


@dataclass
class Audit:
    outcome: str
    problems: list[str] = field(default_factory=list)
    max_leaders: int = 0
    max_leader1: int = 0
    lights_used: set[str] = field(default_factory=set)
    moves: int = 0
    events: int = 0

    @property
    def ok(self) -> bool:
        return not self.problems


def same_shape(points: list[Point], pattern: list[Point]) -> bool:
    """Independent of the engine: equal up to translation or translation after a mirror in y."""

    def canon(ps: list[Point]) -> list[Point]:
        x0 = min(p[0] for p in ps)
        y0 = min(p[1] for p in ps)
        return sorted((x - x0, y - y0) for x, y in ps)

    return canon(points) in (canon(pattern), canon([(x, -y) for x, y in pattern]))


def audit_run(
    engine: Engine, scheduler: str, seed: int, on_compute: Callable[[Engine, int], None] | None = None
) -> Audit:
    """Run to the end, checking after every step: at most one robot ever has light ``leader``.
    ``on_compute(engine, robot)`` is called after every Compute (tests check its explanation there)."""
    sched = make_scheduler(scheduler)
    audit = Audit(outcome="running")
    with collector_paused():
        _audited_steps(engine, sched, seed, audit, on_compute)
    st = engine.state
    audit.outcome = st.outcome or "running"
    audit.lights_used = set(st.lights_used)
    audit.moves, audit.events = st.moves, st.events
    if audit.outcome != "formed":
        audit.problems.append(f"outcome {audit.outcome}")
    if audit.max_leaders > 1:
        audit.problems.append(f"{audit.max_leaders} robots had light leader at once")
    if len(audit.lights_used) > 8:
        audit.problems.append(f"{len(audit.lights_used)} lights used")
    if st.events and any(light != "done" for light in st.lights):  # (no event: formed at time 0)
        audit.problems.append(f"not all done at the end: {sorted(set(st.lights))}")
    if not same_shape(engine.current_points(), list(engine.pattern)):
        if audit.outcome == "formed":
            audit.problems.append("the engine says formed but the shape differs")
        else:
            audit.problems.append("final positions are not the pattern")
    return audit


def _audited_steps(
    engine: Engine,
    sched: Scheduler,
    seed: int,
    audit: Audit,
    on_compute: Callable[[Engine, int], None] | None,
) -> None:
    # A walk keeps every light (core/fast_forward.py), so it needs no check; a caller that looks at every
    # Compute gets them all.
    walks = on_compute is None and getattr(sched, "forced_when_alone", False)
    while not engine.finished:
        if walks and engine.walk() and engine.finished:
            break
        events = engine.apply(sched.choose(engine, step_rng(seed, engine.step_index)))
        if events[-1].phase == "compute":  # lights change at Compute only
            if on_compute is not None:
                for event in events:
                    if event.phase == "compute":
                        on_compute(engine, event.robot)
            lights = engine.state.lights
            audit.max_leaders = max(audit.max_leaders, lights.count("leader"))
            audit.max_leader1 = max(audit.max_leader1, lights.count("leader1"))


def random_solvable_start(k: int, rng: random.Random, box: int | None = None) -> list[Point]:
    side = box or max(3, int((3 * k) ** 0.5) + 1)
    cells = [(x, y) for x in range(side) for y in range(side)]
    while True:
        pts = rng.sample(cells, k)
        if unsolvable_axis(pts) is None:
            return pts


def random_pattern(k: int, rng: random.Random, box: int | None = None) -> list[Point]:
    side = box or max(3, int((3 * k) ** 0.5) + 1)
    return rng.sample([(x, y) for x in range(side) for y in range(side)], k)
