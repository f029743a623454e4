"""Schedules: the adversary as a file, apart from any algorithm.

A trace records what robots saw and decided, so it belongs to one algorithm. A schedule records only
who was activated: ``{"robot": 3, "phase": "look"}`` (one ASYNC event) or ``{"round": [0, 2, 5]}`` (an
SSYNC/FSYNC round: those robots Look, then Compute, then Move together). Which phase a robot is in
depends only on how often it was activated, never on what it decided, so the same schedule drives any
algorithm — the point: the same adversary against two variants.

The adversary also chooses each robot's y-axis, and a run replays only with the flips it was recorded
with: so the header carries them, and the light semantics, ``{"format": "apf-viz-schedule", "version":
2, "robots": k, "y_up": [...], "light_semantics": "compute"}``; then one line per event or round (JSON
Lines, hand-editable). A version-1 header (``robots`` only) still loads; then the robots file or the
seed decides the flips, and the caller warns. A line that names a robot that does not exist, or a phase
that is not that robot's next one, is refused with its line number when the run reaches it.
"""

from __future__ import annotations

import json
from array import array
from collections.abc import Iterable, Iterator, Sequence
from pathlib import Path
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, StrictBool, StrictInt, model_validator

from apf_viz.core.engine import Engine, LightSemantics
from apf_viz.core.files import read_lines
from apf_viz.core.formats import InputError, _parse_json, _validate, header_line, numbered_lines
from apf_viz.core.history import Event, RecordedStep
from apf_viz.core.run import steps_of_trace

SCHEDULE_FORMAT = "apf-viz-schedule"
SCHEDULE_VERSION = 2
Phase = Literal["look", "compute", "move"]
PHASES: tuple[Phase, ...] = ("look", "compute", "move")
_PHASE_CODE = {p: i for i, p in enumerate(PHASES)}
# A schedule line is one event or round: a file of many million lines is the adversary of a long run.
# Parsed lines are kept as two integers each (line number, code), not as objects: 16 bytes a line.
MAX_SCHEDULE_BYTES = 200_000_000


class Found(BaseModel):
    """What the search that wrote a schedule says of it: ``apf-viz adversary`` maximised ``maximize`` and
    reached ``value``, against the built-in schedulers' ``built_ins`` over seeds 0–19, in ``tried``
    schedules (explore/adversary.py); ``apf-viz check --worst`` (``by`` "check") found ``value`` to be the
    exact worst over every schedule, in ``states`` states (explore/worst.py)."""

    model_config = ConfigDict(extra="forbid")
    maximize: Literal["moves", "events"]
    value: StrictInt = Field(ge=0)
    by: Literal["adversary", "check"] = "adversary"
    built_ins: StrictInt | None = Field(default=None, ge=0)
    tried: StrictInt | None = Field(default=None, ge=0, description="schedules the search tried")
    states: StrictInt | None = Field(default=None, ge=0, description="states the exact search explored")

    def words(self) -> str:
        """The search's claim in one sentence, as the schedule's reader is told it."""
        if self.by == "check":
            return (
                f"the worst any schedule forces, by apf-viz check --worst: {self.value:,} {self.maximize} "
                f"(exact: every schedule explored, {self.states or 0:,} states)"
            )
        return (
            f"the worst found by apf-viz adversary: {self.value:,} {self.maximize} "
            f"(the built-in schedulers' most: {self.built_ins or 0:,}; {self.tried or 0:,} schedules tried)"
        )


class ScheduleHeader(BaseModel):
    """Version 2 records the whole adversary: who acts (the lines) and each robot's y-axis (``y_up``),
    and the light semantics the schedule was recorded under. Version 1 had only ``robots``."""

    model_config = ConfigDict(extra="forbid")
    format: Literal["apf-viz-schedule"]
    version: Literal[1, 2]
    robots: StrictInt = Field(ge=1, description="how many robots the schedule is for")
    y_up: list[StrictBool] | None = None
    light_semantics: Literal["compute", "lc-atomic"] | None = None
    found: Found | None = None  # written by apf-viz adversary

    @model_validator(mode="after")
    def _check(self) -> ScheduleHeader:
        if self.y_up is not None and len(self.y_up) != self.robots:
            raise ValueError(f"y_up has {len(self.y_up)} entries for {self.robots} robots")
        return self


NOTE_LENGTH = 300
"""A line's note, at most this many characters: words for the Last event line, not a document."""


class Activation(BaseModel):
    """One ASYNC event: this robot's next phase, which must be ``phase``. A robot that does not exist
    (a negative number included) is refused when the run reaches it, so that the run so far is kept.
    ``note``: what the person who wrote the line wants said when it is played."""

    model_config = ConfigDict(extra="forbid", frozen=True)
    robot: StrictInt
    phase: Phase
    note: str | None = Field(default=None, max_length=NOTE_LENGTH)


class Round(BaseModel):
    """One synchronous round: these robots (all idle) Look, Compute and Move together."""

    model_config = ConfigDict(extra="forbid", frozen=True)
    round: list[StrictInt] = Field(min_length=1)
    note: str | None = Field(default=None, max_length=NOTE_LENGTH)


Line = Activation | Round


class Schedule:
    """A parsed schedule: ``k`` robots, the flips and light semantics it was recorded with (None in a
    version-1 file), and its lines, each with its line number in the file.

    An activation of robot 0 ≤ r < k is stored as the integer ``3·r + phase``; any other line (a round,
    or an activation of a robot that does not exist, refused when followed: the run up to it is kept)
    as ``-1 - i``, the i-th of ``_others`` (an index as large as 10^23 would not fit the array)."""

    __slots__ = ("_codes", "_numbers", "_others", "found", "k", "light_semantics", "notes", "y_up")

    def __init__(
        self, k: int, y_up: Sequence[bool] | None = None, light_semantics: LightSemantics | None = None
    ) -> None:
        self.k = k
        self.y_up = tuple(y_up) if y_up is not None else None
        self.light_semantics = light_semantics
        self._numbers = array("q")
        self._codes = array("q")
        self._others: list[Line] = []
        self.notes: dict[int, str] = {}  # line number → the note written on that line
        self.found: Found | None = None  # the searched adversary's words on it, if it wrote it

    def add(self, number: int, line: Line) -> None:
        """Add the line numbered ``number`` in the file (its note kept too)."""
        if line.note:
            self.notes[number] = line.note
        if isinstance(line, Activation) and 0 <= line.robot < self.k:
            self._add_activation(number, line.robot, _PHASE_CODE[line.phase])
            return
        self._numbers.append(number)
        self._codes.append(-1 - len(self._others))
        self._others.append(line)

    def _add_activation(self, number: int, robot: int, phase: int) -> None:
        self._numbers.append(number)
        self._codes.append(3 * robot + phase)

    def __len__(self) -> int:
        return len(self._codes)

    def __iter__(self) -> Iterator[tuple[int, int | None, Phase | tuple[int, ...]]]:
        """(line number, robot, phase) for an activation, (line number, None, robots) for a round."""
        others = self._others
        for n, code in zip(self._numbers, self._codes, strict=True):
            if code >= 0:
                robot, phase = divmod(code, 3)
                yield n, robot, PHASES[phase]
                continue
            line = others[-1 - code]
            if isinstance(line, Round):
                yield n, None, tuple(line.round)
            else:
                yield n, line.robot, line.phase


def _parse_line(raw: str, where: str, schedule: Schedule, n: int) -> None:
    data = _parse_json(raw, where)
    # The common line, checked by hand: a million lines through pydantic cost 47 s.
    if (
        type(data) is dict
        and len(data) == 2
        and type(data.get("robot")) is int
        and 0 <= data["robot"] < schedule.k
    ):
        phase = _PHASE_CODE.get(data.get("phase"))  # type: ignore[arg-type]
        if phase is not None:
            schedule._add_activation(n, data["robot"], phase)
            return
    line: Line
    if isinstance(data, dict) and "round" in data:
        line = round_line = _validate(Round, data, where)
        if len(set(round_line.round)) != len(round_line.round):
            raise InputError(f"{where}: a robot is listed twice in one round")
    else:
        line = _validate(Activation, data, where)  # only to say what is wrong with it
    schedule.add(n, line)


def _other_format(data: object, where: str) -> None:
    if isinstance(data, dict) and data.get("format") == "apf-viz-trace":
        raise InputError(
            f"{where}: this is a trace, not a schedule; replay it with apf-viz replay --trace, or take its "
            "schedule with apf-viz schedule --from-trace"
        )


def parse_schedule_lines(numbered: Iterable[tuple[int, str]], where: str = "schedule") -> Schedule:
    """A schedule from its non-blank lines, each with its line number (read as they come)."""
    lines, n0, data = header_line(numbered, where, "schedule")
    _other_format(data, where)
    header = _validate(ScheduleHeader, data, f"{where}:{n0}")
    schedule = Schedule(header.robots, header.y_up, header.light_semantics)
    schedule.found = header.found
    for n, raw in lines:
        _parse_line(raw, f"{where}:{n}", schedule, n)
    return schedule


def parse_schedule(text: str, where: str = "schedule") -> Schedule:
    """A schedule from its whole text (blank lines skipped)."""
    return parse_schedule_lines(numbered_lines(text), where)


def load_schedule(path: Path | str) -> Schedule:
    """Read a schedule file (at most :data:`MAX_SCHEDULE_BYTES`), line by line as it comes."""
    return parse_schedule_lines(read_lines(path, MAX_SCHEDULE_BYTES), str(path))


def schedule_text(
    k: int,
    lines: Iterable[Line],
    y_up: Sequence[bool] | None = None,
    light_semantics: str | None = None,
    found: Found | None = None,
) -> str:
    """A schedule file; ``y_up`` and ``light_semantics`` make it the whole adversary (version 2);
    ``found``: the searched adversary's words on it."""
    header: dict[str, Any] = {"format": SCHEDULE_FORMAT, "version": SCHEDULE_VERSION, "robots": k}
    if y_up is not None:
        header["y_up"] = [bool(u) for u in y_up]
    if light_semantics is not None:
        header["light_semantics"] = light_semantics
    if found is not None:
        header["found"] = found.model_dump()
    body = (json.dumps(line.model_dump(exclude_none=True)) for line in lines)
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


def check_robots(schedule: Schedule, k: int, where: str = "schedule") -> None:
    """Refuse, before any step, a schedule written for another number of robots."""
    if schedule.k != k:
        raise InputError(f"{where}: a schedule for {schedule.k} robots, but the run has {k}")


def follow(engine: Engine, schedule: Schedule, where: str = "schedule") -> Iterator[int]:
    """Drive ``engine`` by the schedule, line by line, until its end or the run's end; yields each line
    number after it ran. A robot whose activation changes nothing is activated as written. (The flips
    and light semantics are the engine's: :func:`adversary_flips` says which flips to build it with.)"""
    check_robots(schedule, engine.k, where)
    engine.counts_passed_over = False  # the schedule chooses: no scheduler passes anyone over
    try:
        yield from _follow(engine, schedule, where)
    finally:
        engine.counts_passed_over = True


def _follow(engine: Engine, schedule: Schedule, where: str) -> Iterator[int]:
    lc_atomic = engine.light_semantics == "lc-atomic"
    k = engine.k
    for n, robot, what in schedule:
        if engine.finished:
            return
        # Checked here, not when the file is read, so that the run up to a bad line is kept.
        robots = (robot,) if robot is not None else what
        assert not isinstance(robots, str)  # a line names a robot and its phase, or a round's robots
        missing = [r for r in robots if not 0 <= r < k]
        if missing:
            raise ScheduleError(f"{where}:{n}: robot {missing[0]} does not exist ({k} robots)")
        if robot is not None:
            now = engine.next_event(robot)
            if now != what:
                raise ScheduleError(f"{where}:{n}: robot {robot}'s next phase is {now}, not {what}")
            engine.step([robot])
        else:
            _follow_round(engine, what, where, n, lc_atomic)  # type: ignore[arg-type]
        yield n


def _follow_round(engine: Engine, robots: tuple[int, ...], where: str, n: int, lc_atomic: bool) -> None:
    busy = [r for r in robots if engine.next_event(r) != "look"]
    if busy:
        raise ScheduleError(
            f"{where}:{n}: a round starts with its robots idle; robot {busy[0]}'s next phase is "
            f"{engine.next_event(busy[0])}"
        )
    number = engine.state.round + 1
    for _ in range(2 if lc_atomic else 3):  # Look (+Compute under lc-atomic), Compute, Move
        if engine.finished:
            break
        engine.step(robots, round=number)


def adversary_flips(
    schedule: Schedule,
    file_y_up: Sequence[bool] | None,
    prefer: Literal["schedule", "file"] | None,
    where: str,
    robots_where: str,
) -> tuple[tuple[bool, ...] | None, str | None]:
    """The y-axes a run following ``schedule`` uses (None: the seed decides) and a warning, if any.

    The schedule's flips win over the seed; a robots file that states other flips contradicts it, and
    is refused unless ``prefer`` says which of the two to take."""
    if schedule.y_up is None:
        decider = "the robots file's y_up" if file_y_up is not None else "--seed"
        return (tuple(file_y_up) if file_y_up is not None else None), (
            f"{where} records no y-axis flips (as a version-1 schedule): {decider} decides them, so the run "
            "may not be the one recorded"
        )
    if file_y_up is None or tuple(file_y_up) == schedule.y_up or prefer == "schedule":
        return schedule.y_up, None
    if prefer == "file":
        return tuple(file_y_up), None
    r = next(i for i, (a, b) in enumerate(zip(file_y_up, schedule.y_up, strict=True)) if a != b)
    raise InputError(
        f"{robots_where}: its y_up contradicts the flips {where} was recorded with (robot {r}: "
        f"{'up' if file_y_up[r] else 'flipped'} in the file, {'up' if schedule.y_up[r] else 'flipped'} "
        "in the schedule); --flips schedule or --flips file chooses"
    )
