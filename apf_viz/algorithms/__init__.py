"""The algorithm registry: built-in algorithms by name, and ``module:attribute`` for your own."""

from __future__ import annotations

import importlib
from collections.abc import Callable

from apf_viz.algorithms.apf_opaque_grid import ApfOpaqueGrid
from apf_viz.algorithms.examples import CompactLeft, Stay
from apf_viz.core.algorithm import Algorithm

ALGORITHMS: dict[str, Callable[[], Algorithm]] = {
    "apf-opaque-grid": lambda: ApfOpaqueGrid.parse("apf-opaque-grid"),
    "apf-opaque-grid-literal": lambda: ApfOpaqueGrid.parse("apf-opaque-grid-literal"),
    "stay": Stay,
    "compact-left": CompactLeft,
}

DEFAULT_ALGORITHM = "apf-opaque-grid"


def get_algorithm(name: str) -> Algorithm:
    """A registered algorithm, or ``package.module:Name`` (a class or factory taking no arguments)."""
    if name in ALGORITHMS:
        return ALGORITHMS[name]()
    if name.startswith("apf-opaque-grid@"):
        return ApfOpaqueGrid.parse(name)
    if ":" in name:
        module, _, attr = name.partition(":")
        try:
            factory = getattr(importlib.import_module(module), attr)
        except (ImportError, AttributeError) as e:
            raise ValueError(f"cannot load algorithm {name!r}: {e}") from None
        algo = factory()
        if not isinstance(algo, Algorithm):
            raise ValueError(f"{name!r} is not an algorithm (needs name, lights and decide())")
        return algo
    raise ValueError(f"unknown algorithm {name!r}; choose one of {', '.join(ALGORITHMS)} or module:Name")
