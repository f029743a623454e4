"""Files that come in from a browser (uploads, demo picks): size limits, decoding, parsing, one-line
errors. Nothing here changes a run; the session decides what a parsed file does."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from apf_viz.algorithms import Factory, get_algorithm
from apf_viz.core.engine import Engine
from apf_viz.core.formats import (
    InputError,
    PatternFile,
    RobotsFile,
    TraceHeader,
    parse_pattern,
    parse_robots,
    parse_trace,
)
from apf_viz.core.run import engine_for_trace, replay
from apf_viz.core.schedule import Schedule, parse_schedule
from apf_viz.lecture import MAX_LECTURE_BYTES, Lecture, parse_lecture

MAX_UPLOAD_BYTES = 2_000_000  # robots and pattern files from a browser
MAX_TRACE_UPLOAD_BYTES = 50_000_000  # a trace from a browser: about 500,000 events


def decode(filename: str, content: bytes, limit: int = MAX_UPLOAD_BYTES) -> str:
    """An upload's text: at most ``limit`` bytes of UTF-8, or an :class:`InputError` naming ``filename``."""
    if len(content) > limit:
        raise InputError(f"{filename}: file is too large ({len(content):,} bytes, limit {limit:,})")
    try:
        return content.decode("utf-8")
    except UnicodeDecodeError:
        raise InputError(f"{filename}: not UTF-8 text") from None


def robots_upload(filename: str, content: bytes) -> RobotsFile:
    """A robots file uploaded, checked."""
    return parse_robots(decode(filename, content), filename)


def pattern_upload(filename: str, content: bytes) -> PatternFile:
    """A pattern file uploaded, checked."""
    return parse_pattern(decode(filename, content), filename)


def lecture_upload(filename: str, content: bytes) -> Lecture:
    """A lecture uploaded, checked (at most :data:`MAX_LECTURE_BYTES`)."""
    return parse_lecture(decode(filename, content, MAX_LECTURE_BYTES), filename)


def schedule_upload(filename: str, content: bytes) -> Schedule:
    """A schedule uploaded, parsed (at most :data:`MAX_TRACE_UPLOAD_BYTES`)."""
    return parse_schedule(decode(filename, content, MAX_TRACE_UPLOAD_BYTES), filename)


@dataclass(frozen=True)
class LoadedTrace:
    """A trace uploaded: its header, the engine that replayed it and how many events it holds."""

    header: TraceHeader
    engine: Engine  # replayed to the trace's end, every event checked
    events: int  # how many events the trace holds


def trace_upload(
    filename: str,
    content: bytes,
    plugins: Mapping[str, Factory],
    max_events: int,
    limit: int = MAX_TRACE_UPLOAD_BYTES,
) -> LoadedTrace:
    """Parse a trace and replay it event by event. Its algorithm must be built in or one of the
    command line's ``plugins``: a file never loads code. ``limit``: bytes accepted (a browser's upload,
    unless the command line opened the file)."""
    header, events = parse_trace(decode(filename, content, limit), filename)
    try:
        algorithm = get_algorithm(header.algorithm, plugins)
    except ValueError as e:
        raise InputError(f"{filename}: {e}") from None
    engine = engine_for_trace(header, algorithm, max(max_events, len(events) + 1))
    replay(engine, events, filename)
    return LoadedTrace(header, engine, len(events))
