"""The built-in demo's session: a heart from 10 robots (what `apf-viz` opens, what figures and exported
pages start from). No viser: the figure and export commands build it without a server."""

from __future__ import annotations

from typing import Any

from apf_viz.core.formats import load_pattern, load_robots
from apf_viz.core.grid import as_point
from apf_viz.demos import DEMO_PATTERN, DEMO_START
from apf_viz.workbench.session import Session


def demo_session(**options: Any) -> Session:
    """The built-in demo: a heart from 10 robots. ``options`` go to :class:`Session`."""
    robots = load_robots(DEMO_START)
    pattern = load_pattern(DEMO_PATTERN)
    options.setdefault("seed", 1)
    return Session(
        [as_point(p) for p in robots.robots],
        [as_point(p) for p in pattern.points],
        y_up=robots.flips(options["seed"]),
        **options,
    )
