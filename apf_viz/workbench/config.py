"""A session from a plain config: what ``apf-viz serve`` starts with, built without viser and without the
command line (which only fills a :class:`SessionConfig` in, cli/serve.py), so a script can build the same
session and ``ui/`` is handed a session, never argparse's Namespace."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from apf_viz.algorithms import DEFAULT_ALGORITHM, algorithm_from_command_line
from apf_viz.core.files import read_bytes
from apf_viz.core.formats import (
    MAX_TRACE_BYTES,
    InputError,
    check_sizes,
    load_pattern,
    load_robots,
    load_trace,
)
from apf_viz.core.grid import as_point
from apf_viz.core.schedulers import DEFAULT_SCHEDULER
from apf_viz.demos import DEMO_PATTERN, DEMO_START
from apf_viz.lecture import find_lecture
from apf_viz.workbench.library import PatternLibrary
from apf_viz.workbench.session import Session
from apf_viz.workbench.session.demo import demo_session


@dataclass(frozen=True)
class SessionConfig:
    """What a session starts with. Paths are files (a shipped name is resolved by the caller); ``demo``
    is a Demo scenario's title (:func:`apf_viz.demos.find_scenario`); ``lecture`` a lecture's file or
    shipped name, opened at its first stop."""

    robots: Path | None = None
    pattern: Path | None = None
    trace: Path | None = None
    demo: str | None = None
    lecture: str | None = None
    library: Path | None = None
    algorithm: str = DEFAULT_ALGORITHM
    scheduler: str = DEFAULT_SCHEDULER
    seed: int = 1
    light_semantics: str = "compute"


def session_from_config(config: SessionConfig) -> Session:
    """The session a config describes, or an :class:`InputError` in one line (a bad file, a lecture that
    does not load) before any server starts. ``algorithm`` may load a plug-in (``module:Class``: the
    config comes from the command line or a script, never from a page); a trace then names only
    built-ins or that plug-in."""
    session = _run_of(config)
    if config.library is not None:
        session.use_library(PatternLibrary(config.library))
    if config.lecture is not None:
        session.start_lecture(find_lecture(config.lecture))
    return session


def _run_of(config: SessionConfig) -> Session:
    algorithm, plugins = algorithm_from_command_line(config.algorithm or DEFAULT_ALGORITHM)
    name, scheduler, seed = algorithm.name, config.scheduler, config.seed
    if config.trace:
        session = demo_session(algorithm=name, scheduler=scheduler, seed=seed, plugins=plugins)
        path = Path(config.trace)
        load_trace(path)  # validates the file with a one-line error before the UI starts
        session.load_trace(path.name, read_bytes(path, MAX_TRACE_BYTES), MAX_TRACE_BYTES)
        return session
    robots = load_robots(config.robots) if config.robots else load_robots(DEMO_START)
    pattern = load_pattern(config.pattern) if config.pattern else load_pattern(DEMO_PATTERN)
    if config.pattern is None and len(pattern.points) != len(robots.robots):
        raise InputError(
            f"{config.robots}: {len(robots.robots)} robots, but the default pattern (the demo's heart) "
            f"has {len(pattern.points)} points: pass --pattern"
        )
    check_sizes(robots, pattern, str(config.pattern or DEMO_PATTERN))
    session = Session(
        [as_point(p) for p in robots.robots],
        [as_point(p) for p in pattern.points],
        y_up=robots.flips(config.seed),
        light_semantics=config.light_semantics,
        plugins=plugins,
        algorithm=name,
        scheduler=scheduler,
        seed=seed,
    )
    if config.demo:
        session.load_scenario(config.demo)  # a Demo scenario by its title (serve --demo)
    return session
