"""Driving a run: a scheduler chooses, the engine steps, until an outcome. Also traces and replay."""

from __future__ import annotations

import gc
import json
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

from apf_viz.core.algorithm import Algorithm
from apf_viz.core.budget import paper_D
from apf_viz.core.engine import Engine, EngineError
from apf_viz.core.formats import InputError, TraceHeader, event_to_json
from apf_viz.core.grid import Point, as_point
from apf_viz.core.history import Event, StepRecord
from apf_viz.core.schedulers import Scheduler, step_rng


@contextmanager
def collector_paused() -> Iterator[None]:
    """Pause Python's cyclic garbage collector while an engine steps; restore it on exit.

    The engine makes no reference cycles (its records are tuples, lists and dicts of values), so
    reference counting frees all it drops. But the collector's full passes walk every snapshot that the
    robots and the checkpoints hold, and they come often because every Look's snapshot outlives the
    young generations: at k = 100 under ASYNC they cost as much as the run itself
    (docs/PERFORMANCE.md)."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()


def advance(engine: Engine, scheduler: Scheduler, seed: int, steps: int | None = None) -> int:
    """Let the scheduler drive the engine for ``steps`` steps, or until the run ends. Returns steps taken."""
    taken = 0
    # A lone eligible robot is what such a scheduler must choose: its repeating cycles may be one walk.
    walks = engine.fast_forward and getattr(scheduler, "forced_when_alone", False)
    with collector_paused():
        while not engine.finished and (steps is None or taken < steps):
            if walks:
                taken += engine.walk(None if steps is None else steps - taken)
                if engine.finished or (steps is not None and taken >= steps):
                    break
            engine.apply(scheduler.choose(engine, step_rng(seed, engine.step_index)))
            taken += 1
    return taken


@dataclass(frozen=True)
class RunSummary:
    """What ``apf-viz run --json`` prints."""

    outcome: str
    final: list[Point]
    k: int
    D: int  # max(m, n, M, N, k) of the paper
    moves: int
    events: int
    cycles: int
    skipped: int  # robot·steps passed over because their next cycle could change nothing
    moves_per_kD: float
    max_moves: int | None  # the run's caps (its budget unless the command line gave them)
    max_events: int | None
    lights_used: list[str]
    max_recorded: int | None = None  # steps the run may hold in memory (core/budget.py)

    @classmethod
    def of(cls, engine: Engine, outcome: str | None = None) -> RunSummary:
        """The summary of a run; ``outcome`` overrides "running" (e.g. ``schedule-end``)."""
        st = engine.state
        order = {name: i for i, name in enumerate(engine.algorithm.lights)}
        d = paper_D(engine.start, engine.pattern)
        return cls(
            outcome=st.outcome or outcome or "running",
            final=engine.current_points(),
            k=engine.k,
            D=d,
            moves=st.moves,
            events=st.events,
            cycles=st.cycles,
            skipped=st.skipped,
            moves_per_kD=round(st.moves / (engine.k * d), 6),
            max_moves=engine.max_moves,
            max_events=engine.max_events,
            lights_used=sorted(st.lights_used, key=lambda s: order.get(s, len(order))),
            max_recorded=engine.max_recorded,
        )


def trace_header(
    engine: Engine, scheduler: str, seed: int | None, options: dict[str, Any] | None = None
) -> TraceHeader:
    """The first line of the engine's trace file: its start, flips, pattern and algorithm, how it was
    scheduled, and the run's ``options``."""
    return TraceHeader(
        format="apf-viz-trace",
        version=1,
        robots=list(engine.start),
        y_up=list(engine.y_up),
        pattern=list(engine.pattern),
        scheduler=scheduler,
        seed=seed,
        algorithm=engine.algorithm.name,
        light_semantics=engine.light_semantics,
        options=options or {},
    )


def engine_for_trace(header: TraceHeader, algorithm: Algorithm, max_events: int | None = None) -> Engine:
    """A fresh engine with the trace's start, pattern, flips and light semantics. It keeps every
    activation: a replay applies recorded steps, and a trace may hold no-op cycles (one written with
    ``--all-activations``, or before skipping existed) that a skipping engine would refuse to run."""
    return Engine(
        [as_point(p) for p in header.robots],
        [as_point(p) for p in header.pattern],
        algorithm,
        y_up=header.y_up,
        light_semantics=header.light_semantics,
        max_events=max_events,
        skip_noops=False,
    )


def steps_of_trace(events: Sequence[Event], lc_atomic: bool) -> list[StepRecord]:
    """Regroup trace events into engine steps: consecutive events of one synchronous round and phase
    form one step; under lc-atomic a Look and the Compute the engine adds to it are one step."""
    steps: list[StepRecord] = []
    i = 0
    while i < len(events):
        e = events[i]
        j = i + 1
        if e.round is not None:
            while j < len(events) and events[j].round == e.round and events[j].phase == e.phase:
                j += 1
        robots = tuple(ev.robot for ev in events[i:j])
        if lc_atomic and e.phase == "look":
            n = j - i
            tail = events[j : j + n]
            if len(tail) != n or any(
                t.phase != "compute" or t.robot != r for t, r in zip(tail, robots, strict=True)
            ):
                raise InputError(
                    f"trace: under lc-atomic the Look of robot {e.robot} must be followed by its Compute"
                )
            j += n
        steps.append(StepRecord(robots, e.round))
        i = j
    return steps


def replay(engine: Engine, events: Sequence[Event], where: str = "trace") -> None:
    """Apply a recorded schedule to a fresh engine and check that every event comes out identical."""
    done = 0
    for record in steps_of_trace(events, engine.light_semantics == "lc-atomic"):
        want = events[done]
        if engine.finished:
            raise InputError(f"{where}: event {done + 1} comes after the run ended ({engine.outcome})")
        if engine.next_event(want.robot) != want.phase:
            raise InputError(
                f"{where}: event {done + 1}: robot {want.robot} cannot {want.phase} now, "
                f"its next event is {engine.next_event(want.robot)}"
            )
        try:
            produced = engine.step(record.robots, round=record.round)
        except EngineError as e:
            raise InputError(f"{where}: event {done + 1} cannot be replayed: {e}") from None
        for got in produced:
            want = events[done]
            if want.rule_id is None:  # a trace written before rule ids: the prose rule still must match
                got = got._replace(rule_id=None)
            if got != want:
                recorded, produced_now = json.dumps(event_to_json(want)), json.dumps(event_to_json(got))
                raise InputError(
                    f"{where}: event {done + 1} differs on replay: recorded {recorded}, got {produced_now}"
                )
            done += 1
    if not engine.finished:
        engine.settle_outcome()  # a trace that ends where nobody can act ends the run there (stuck)
