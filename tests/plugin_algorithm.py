"""A plug-in algorithm for the tests: what a user's own ``--algorithm tests.plugin_algorithm:Hop`` is."""

from __future__ import annotations

from apf_viz.algorithms.examples import CompactLeft


class Hop(CompactLeft):
    """CompactLeft under a name the registry does not know."""

    name = "test-hop"
