"""Schedules: the adversary as a file, apart from any algorithm.

A trace records what robots saw and decided, so it belongs to one algorithm. A schedule records only
who was activated: ``{"robot": 3, "phase": "look"}`` (one ASYNC event) or ``{"round": [0, 2, 5]}`` (an
SSYNC/FSYNC round: those robots Look, then Compute, then Move together). Which phase a robot is in
depends only on how often it was activated, never on what it decided, so the same schedule drives any
algorithm — the point: the same adversary against two variants.

File: a header line ``{"format": "apf-viz-schedule", "version": 1, "robots": k}``, then one line per
event or round (JSON Lines, hand-editable). A line that names a robot that does not exist, or a phase
that is not that robot's next one, is refused with its line number.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Iterator, Sequence
from pathlib import Path
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, StrictInt

from apf_viz.core.engine import Engine
from apf_viz.core.formats import MAX_TRACE_BYTES, InputError, _parse_json, _read_text, _validate
from apf_viz.core.history import Event, RecordedStep
from apf_viz.core.run import steps_of_trace

SCHEDULE_FORMAT = "apf-viz-schedule"
SCHEDULE_VERSION = 1
Phase = Literal["look", "compute", "move"]


class ScheduleHeader(BaseModel):
    model_config = ConfigDict(extra="forbid")
    format: Literal["apf-viz-schedule"]
    version: Literal[1]
    robots: StrictInt = Field(ge=1, description="how many robots the schedule is for")


class Activation(BaseModel):
    """One ASYNC event: this robot's next phase, which must be ``phase``."""

    model_config = ConfigDict(extra="forbid", frozen=True)
    robot: StrictInt = Field(ge=0)
    phase: Phase


class Round(BaseModel):
    """One synchronous round: these robots (all idle) Look, Compute and Move together."""

    model_config = ConfigDict(extra="forbid", frozen=True)
    round: list[StrictInt] = Field(min_length=1)


Line = Activation | Round


class Schedule(BaseModel):
    """A parsed schedule: ``k`` robots and its lines, each with its line number in the file."""

    k: int
    lines: list[tuple[int, Line]]


def _line(data: object, where: str) -> Line:
    if isinstance(data, dict) and "round" in data:
        return _validate(Round, data, where)
    return _validate(Activation, data, where)


def parse_schedule(text: str, where: str = "schedule") -> Schedule:
    numbered = [(n, line) for n, line in enumerate(text.splitlines(), 1) if line.strip()]
    if not numbered:
        raise InputError(f"{where}: empty schedule file")
    n0, first = numbered[0]
    header = _validate(ScheduleHeader, _parse_json(first, f"{where}:{n0}"), f"{where}:{n0}")
    lines: list[tuple[int, Line]] = []
    for n, raw in numbered[1:]:
        line = _line(_parse_json(raw, f"{where}:{n}"), f"{where}:{n}")
        if isinstance(line, Round) and len(set(line.round)) != len(line.round):
            raise InputError(f"{where}:{n}: a robot is listed twice in one round")
        lines.append((n, line))
    return Schedule(k=header.robots, lines=lines)


def load_schedule(path: Path | str) -> Schedule:
    return parse_schedule(_read_text(path, MAX_TRACE_BYTES), str(path))


def schedule_text(k: int, lines: Iterable[Line]) -> str:
    header = {"format": SCHEDULE_FORMAT, "version": SCHEDULE_VERSION, "robots": k}
    body = (json.dumps(line.model_dump()) for line in lines)
    return "\n".join([json.dumps(header), *body]) + "\n"


def schedule_of_steps(steps: Iterable[RecordedStep]) -> list[Line]:
    """The schedule of recorded engine steps: one line per ASYNC event, one per synchronous round (its
    Look, Compute and Move steps, or under lc-atomic its Look+Compute and Move steps, share a round)."""
    lines: list[Line] = []
    current: int | None = None
    for step in steps:
        record, events = step
        if record.round is None:
            for ev in events[:1]:  # under lc-atomic a Look brings its Compute: one activation
                lines.append(Activation(robot=ev.robot, phase=ev.phase))
        elif record.round != current:
            current = record.round
            lines.append(Round(round=sorted(record.robots)))
    return lines


def schedule_of_trace(events: Sequence[Event], lc_atomic: bool) -> list[Line]:
    """A trace's schedule: its events regrouped into the engine steps that made them (the grouping a
    replay uses, ``core.run.steps_of_trace``), then :func:`schedule_of_steps`."""
    steps: list[RecordedStep] = []
    i = 0
    for record in steps_of_trace(events, lc_atomic):
        n = len(record.robots) * (2 if lc_atomic and events[i].phase == "look" else 1)
        steps.append(RecordedStep(record, tuple(events[i : i + n])))
        i += n
    return schedule_of_steps(steps)


class ScheduleError(InputError):
    """A line the run cannot follow (the run so far is kept)."""


def follow(engine: Engine, schedule: Schedule, where: str = "schedule") -> Iterator[int]:
    """Drive ``engine`` by the schedule, line by line, until its end or the run's end; yields each line
    number after it ran. A robot whose activation changes nothing is activated as written."""
    if schedule.k != engine.k:
        raise InputError(f"{where}: a schedule for {schedule.k} robots, but the run has {engine.k}")
    lc_atomic = engine.light_semantics == "lc-atomic"
    for n, line in schedule.lines:
        if engine.finished:
            return
        # Checked here, not when the file is read, so that the run up to a bad line is kept.
        missing = [r for r in (line.round if isinstance(line, Round) else [line.robot]) if r >= engine.k]
        if missing:
            raise ScheduleError(f"{where}:{n}: robot {missing[0]} does not exist ({engine.k} robots)")
        if isinstance(line, Activation):
            now = engine.next_event(line.robot)
            if now != line.phase:
                raise ScheduleError(
                    f"{where}:{n}: robot {line.robot}'s next phase is {now}, not {line.phase}"
                )
            engine.step([line.robot])
        else:
            busy = [r for r in line.round if engine.next_event(r) != "look"]
            if busy:
                raise ScheduleError(
                    f"{where}:{n}: a round starts with its robots idle; robot {busy[0]}'s next phase is "
                    f"{engine.next_event(busy[0])}"
                )
            number = engine.state.round + 1
            for _ in range(2 if lc_atomic else 3):  # Look (+Compute under lc-atomic), Compute, Move
                if engine.finished:
                    break
                engine.step(line.round, round=number)
        yield n
