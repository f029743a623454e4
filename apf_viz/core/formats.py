"""Files: robots, pattern and trace (JSON / JSON Lines), as pydantic models with one-line errors.

Every problem with an input file becomes an :class:`InputError` whose message names the file and the
problem in one line; the CLI prints it and exits 2, the UI shows it as a notification. Writes are atomic:
a temporary file in the same folder, then a rename.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Iterator, Sequence
from pathlib import Path
from typing import Annotated, Any, Literal, TypeVar

from pydantic import BaseModel, ConfigDict, Field, StrictBool, StrictInt, ValidationError, model_validator

from apf_viz.core.files import InputError as InputError  # re-exported: the error of every input file
from apf_viz.core.files import read_lines, read_text
from apf_viz.core.frames import random_y_up
from apf_viz.core.grid import Direction, Point, as_point, coordinate_problem
from apf_viz.core.history import Event

TRACE_FORMAT = "apf-viz-trace"
TRACE_VERSION = 1
MAX_INPUT_BYTES = 5_000_000  # a robots or pattern file read from disk
MAX_TRACE_BYTES = 1_000_000_000  # a trace read from disk: a 100-robot run writes about 300 MB


GridPoint = Annotated[tuple[StrictInt, StrictInt], Field(description="[x, y] on the grid")]


def _check_points(points: Sequence[tuple[int, int]], what: str) -> None:
    """Inside the supported coordinate range, and no two on one point."""
    problem = coordinate_problem(points, what)
    if problem:
        raise ValueError(problem)
    seen: set[tuple[int, int]] = set()
    for p in points:
        if p in seen:
            raise ValueError(f"duplicate {what} at ({p[0]}, {p[1]})")
        seen.add(p)


class RobotsFile(BaseModel):
    """``{"robots": [[x, y], ...], "y_up": [true, false, ...]}``; ``y_up`` is optional."""

    model_config = ConfigDict(extra="forbid")
    robots: list[GridPoint] = Field(min_length=1)
    y_up: list[StrictBool] | None = None

    @model_validator(mode="after")
    def _check(self) -> RobotsFile:
        _check_points(self.robots, "robot")
        if self.y_up is not None and len(self.y_up) != len(self.robots):
            raise ValueError(f"y_up has {len(self.y_up)} entries for {len(self.robots)} robots")
        return self

    def flips(self, seed: int) -> list[bool]:
        """The robots' y-axes: the file's ``y_up``, or, when it gives none, the adversary's random choice
        from ``seed`` (the same in ``run``, ``check``, the visualiser and every upload)."""
        return list(self.y_up) if self.y_up is not None else random_y_up(len(self.robots), seed)


class PatternFile(BaseModel):
    """``{"name": "...", "points": [[x, y], ...]}``; ``name`` is optional."""

    model_config = ConfigDict(extra="forbid")
    name: str | None = None
    points: list[GridPoint] = Field(min_length=1)

    @model_validator(mode="after")
    def _check(self) -> PatternFile:
        _check_points(self.points, "pattern point")
        return self


class TraceHeader(BaseModel):
    """The first line of a trace file."""

    model_config = ConfigDict(extra="forbid")
    format: Literal["apf-viz-trace"]
    version: Literal[1]
    robots: list[GridPoint] = Field(min_length=1)
    y_up: list[StrictBool] | None = None
    pattern: list[GridPoint] = Field(min_length=1)
    scheduler: str
    seed: StrictInt | None = None
    algorithm: str
    light_semantics: Literal["compute", "lc-atomic"] = "compute"
    options: dict[str, Any] = Field(default_factory=dict)

    @model_validator(mode="after")
    def _check(self) -> TraceHeader:
        _check_points(self.robots, "robot")
        _check_points(self.pattern, "pattern point")
        if self.y_up is not None and len(self.y_up) != len(self.robots):
            raise ValueError(f"y_up has {len(self.y_up)} entries for {len(self.robots)} robots")
        problem = size_problem(len(self.pattern), len(self.robots))
        if problem:
            raise ValueError(problem)
        return self


class TraceEvent(BaseModel):
    """One event line of a trace, global frame."""

    model_config = ConfigDict(extra="forbid")
    robot: StrictInt = Field(ge=0)
    phase: Literal["look", "compute", "move"]
    sees: list[StrictInt] | None = None
    light: str | None = None
    move: Literal["left", "right", "up", "down"] | None = None
    rule: str | None = None
    to: GridPoint | None = None
    round: StrictInt | None = None
    collision: bool | None = None
    rule_id: str | None = None

    @model_validator(mode="after")
    def _check(self) -> TraceEvent:
        required = {"look": "sees", "compute": "light", "move": "to"}[self.phase]
        if getattr(self, required) is None:
            raise ValueError(f"a {self.phase} event needs {required!r}")
        return self

    def to_event(self) -> Event:
        """The event this line describes, as the engine records it."""
        return Event(
            robot=self.robot,
            phase=self.phase,
            sees=tuple(self.sees) if self.sees is not None else None,
            light=self.light,
            move=Direction(self.move) if self.move else None,
            rule=self.rule,
            to=as_point(self.to) if self.to is not None else None,
            round=self.round,
            collision=bool(self.collision),
            rule_id=self.rule_id,
        )


def event_to_json(e: Event) -> dict[str, Any]:
    """The trace line of an event (only the fields its phase uses)."""
    out: dict[str, Any] = {"robot": e.robot, "phase": e.phase}
    if e.phase == "look":
        out["sees"] = list(e.sees or ())
    elif e.phase == "compute":
        out["light"] = e.light
        out["move"] = e.move.value if e.move else None
        if e.rule:
            out["rule"] = e.rule
        if e.rule_id:
            out["rule_id"] = e.rule_id
    else:
        out["to"] = list(e.to) if e.to else None
        if e.collision:
            out["collision"] = True
    if e.round is not None:
        out["round"] = e.round
    return out


# ---------------------------------------------------------------------------------------------- reading
def _one_line(err: ValidationError) -> str:
    first = err.errors()[0]
    loc = "".join(f"[{p}]" if isinstance(p, int) else f".{p}" for p in first["loc"]).lstrip(".")
    msg = first["msg"].removeprefix("Value error, ")
    if first["type"] == "model_type":  # "Input should be a valid dictionary or instance of RobotsFile"
        msg = "expected a JSON object (the file formats: apf-viz docs cli)"
    extra = err.error_count() - 1
    more = f" (and {extra} more problem{'s' if extra > 1 else ''})" if extra else ""
    return f"{loc}: {msg}{more}" if loc else f"{msg}{more}"


def numbered_lines(text: str) -> Iterator[tuple[int, str]]:
    """The non-blank lines of a text with their numbers (as :func:`read_lines` gives a file's)."""
    return ((n, line) for n, line in enumerate(text.splitlines(), 1) if line.strip())


def _parse_json(text: str, where: str) -> Any:
    try:
        return json.loads(text)
    except json.JSONDecodeError as e:
        raise InputError(f"{where}: not valid JSON ({e.msg} at line {e.lineno} column {e.colno})") from None
    except RecursionError:
        raise InputError(f"{where}: not valid JSON (nested too deeply)") from None
    except ValueError as e:  # e.g. an integer of more than 4,300 digits
        raise InputError(f"{where}: not valid JSON ({e})") from None


M = TypeVar("M", bound=BaseModel)


def _validate(model: type[M], data: Any, where: str) -> M:
    try:
        return model.model_validate(data)
    except ValidationError as e:
        raise InputError(f"{where}: {_one_line(e)}") from None


def parse_json_model(model: type[BaseModel], text: str, where: str) -> Any:
    """A pydantic model from JSON text; every problem an :class:`InputError` of one line naming
    ``where`` and the field."""
    return _validate(model, _parse_json(text, where), where)


def parse_robots(text: str, where: str = "robots") -> RobotsFile:
    """A robots file from its JSON text; every problem an :class:`InputError` naming ``where``."""
    return _validate(RobotsFile, _parse_json(text, where), where)


def parse_pattern(text: str, where: str = "pattern") -> PatternFile:
    """A pattern file from its JSON text; every problem an :class:`InputError` naming ``where``."""
    return _validate(PatternFile, _parse_json(text, where), where)


def load_robots(path: Path | str) -> RobotsFile:
    """Read and check a robots file (at most :data:`MAX_INPUT_BYTES`)."""
    return parse_robots(read_text(path, MAX_INPUT_BYTES), str(path))


def load_pattern(path: Path | str) -> PatternFile:
    """Read and check a pattern file (at most :data:`MAX_INPUT_BYTES`)."""
    return parse_pattern(read_text(path, MAX_INPUT_BYTES), str(path))


def header_line(
    numbered: Iterable[tuple[int, str]], where: str, what: str
) -> tuple[Iterator[tuple[int, str]], int, Any]:
    """The first line of a JSON Lines file (trace or schedule), parsed, its number, and the rest to come."""
    lines = iter(numbered)
    first = next(lines, None)
    if first is None:
        raise InputError(f"{where}: empty {what} file")
    n0, text = first
    return lines, n0, _parse_json(text, f"{where}:{n0}")


def parse_trace_lines(
    numbered: Iterable[tuple[int, str]], where: str = "trace"
) -> tuple[TraceHeader, list[Event]]:
    """A trace from its non-blank lines, each with its line number (read as they come)."""
    lines, n0, data = header_line(numbered, where, "trace")
    if isinstance(data, dict) and data.get("format") == "apf-viz-schedule":
        raise InputError(
            f"{where}: this is a schedule, not a trace; follow it with apf-viz run --robots R --pattern P "
            f"--schedule {where}"
        )
    header = _validate(TraceHeader, data, f"{where}:{n0}")
    k = len(header.robots)
    events = []
    for n, line in lines:
        ev = _validate(TraceEvent, _parse_json(line, f"{where}:{n}"), f"{where}:{n}")
        if ev.robot >= k:
            raise InputError(f"{where}:{n}: robot {ev.robot} does not exist ({k} robots)")
        if ev.sees is not None and any(not 0 <= s < k for s in ev.sees):
            raise InputError(f"{where}:{n}: sees a robot that does not exist ({k} robots)")
        events.append(ev.to_event())
    return header, events


def parse_trace(text: str, where: str = "trace") -> tuple[TraceHeader, list[Event]]:
    """A trace's header and events from its whole text (blank lines skipped)."""
    return parse_trace_lines(numbered_lines(text), where)


def load_trace(path: Path | str) -> tuple[TraceHeader, list[Event]]:
    """Read a trace file (at most :data:`MAX_TRACE_BYTES`), line by line as it comes."""
    return parse_trace_lines(read_lines(path, MAX_TRACE_BYTES), str(path))


def size_problem(pattern_points: int, robots: int) -> str | None:
    """The pattern must have one point per robot (paper: n = k): what is wrong, or None."""
    if pattern_points == robots:
        return None
    points = f"{pattern_points} point{'s' if pattern_points != 1 else ''}"
    there = f"is {robots} robot" if robots == 1 else f"are {robots} robots"
    return f"the pattern has {points} but there {there}"


def check_sizes(robots: RobotsFile, pattern: PatternFile, pattern_name: str = "pattern") -> None:
    """Refuse a pattern that does not have one point per robot, naming ``pattern_name``."""
    problem = size_problem(len(pattern.points), len(robots.robots))
    if problem:
        raise InputError(f"{pattern_name}: {problem}")


def robots_json(robots: Iterable[Point], y_up: Sequence[bool] | None = None) -> str:
    """A robots file's text: the points, and the flips when given."""
    data: dict[str, Any] = {"robots": [list(p) for p in robots]}
    if y_up is not None:
        data["y_up"] = list(y_up)
    return json.dumps(data) + "\n"


def pattern_json(points: Iterable[Point], name: str | None = None) -> str:
    """A pattern file's text: the points, and the name when given."""
    data: dict[str, Any] = {}
    if name:
        data["name"] = name
    data["points"] = [list(p) for p in points]
    return json.dumps(data) + "\n"


def trace_text(header: TraceHeader, events: Iterable[Event]) -> str:
    """A trace file's text: the header's line, then a line for each event."""
    lines = [header.model_dump_json(exclude_none=True)]
    lines += [json.dumps(event_to_json(e)) for e in events]
    return "\n".join(lines) + "\n"
