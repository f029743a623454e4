"""The run a command draws or records (``figure``, ``export``): a trace's, or a start's under the
adversary's options; every input checked with one-line errors before anything runs."""

from __future__ import annotations

import argparse
from pathlib import Path

from apf_viz.algorithms import algorithm_from_command_line
from apf_viz.cli.common import shipped
from apf_viz.core.files import read_bytes
from apf_viz.core.formats import MAX_TRACE_BYTES, load_pattern, load_robots, load_trace
from apf_viz.core.grid import as_point


def trace_session(trace: Path):
    """A session following the trace ``trace`` (a file, or a shipped name), at its start; its file name."""
    from apf_viz.workbench.session.demo import demo_session

    path = shipped(trace, "trace", "--trace")
    assert path is not None
    load_trace(path)  # a missing or malformed file: one line, before anything
    session = demo_session()
    session.load_trace(path.name, read_bytes(path, MAX_TRACE_BYTES), MAX_TRACE_BYTES)
    return session, path.name


def start_session(args: argparse.Namespace):
    """A session from ``--robots`` and ``--pattern`` (files, or shipped names) under ``--algorithm``,
    ``--scheduler``, ``--seed`` and ``--light-semantics``, at its start; the two files' names."""
    from apf_viz.workbench.session import Session

    robots_path = shipped(args.robots, "robots", "--robots")
    pattern_path = shipped(args.pattern, "pattern", "--pattern")
    assert robots_path is not None and pattern_path is not None
    robots, pattern = load_robots(robots_path), load_pattern(pattern_path)
    algorithm, plugins = algorithm_from_command_line(args.algorithm)
    session = Session(
        [as_point(p) for p in robots.robots],
        [as_point(p) for p in pattern.points],
        y_up=robots.flips(args.seed),
        algorithm=algorithm.name,
        scheduler=args.scheduler,
        seed=args.seed,
        light_semantics=args.light_semantics,
        plugins=plugins,
    )
    return session, robots_path.name, pattern_path.name
