"""The algorithm registry: built-in algorithms by name, and plug-ins the command line loads.

A name that comes from a file or a browser (a trace header, an upload) is resolved by
:func:`get_algorithm`, which never imports anything: it knows the built-in names, the
``apf-opaque-grid@…`` resolution sets, and the plug-ins the person at the command line loaded. Only
:func:`load_plugin`, called for a ``--algorithm module:Name`` typed on the command line, imports code.
"""

from __future__ import annotations

import importlib
import inspect
import os
import sys
from collections.abc import Callable, Mapping
from types import MappingProxyType, ModuleType
from typing import cast

from apf_viz.algorithms.apf_opaque_grid import ApfOpaqueGrid
from apf_viz.algorithms.examples import CompactLeft, Stay
from apf_viz.algorithms.merged_lights import MARKER, merged_algorithm
from apf_viz.core.algorithm import Algorithm

__all__ = [
    "ALGORITHMS",
    "DEFAULT_ALGORITHM",
    "Factory",
    "algorithm_from_command_line",
    "get_algorithm",
    "load_plugin",
]

Factory = Callable[[], Algorithm]

ALGORITHMS: Mapping[str, Factory] = MappingProxyType(
    {
        "apf-opaque-grid": lambda: ApfOpaqueGrid.parse("apf-opaque-grid"),
        "apf-opaque-grid-literal": lambda: ApfOpaqueGrid.parse("apf-opaque-grid-literal"),
        "stay": Stay,
        "compact-left": CompactLeft,
    }
)

DEFAULT_ALGORITHM = "apf-opaque-grid"
_VARIANT_PREFIX = "apf-opaque-grid@"


def get_algorithm(name: str, plugins: Mapping[str, Factory] | None = None) -> Algorithm:
    """A built-in algorithm, a resolution set ``apf-opaque-grid@R1,R2``, or one of ``plugins`` (the
    algorithms the command line loaded, by their spec and their name). Imports nothing: safe for names
    read from files and browsers. Raises ``ValueError`` with a one-line message for any other name."""
    if name in ALGORITHMS:
        return ALGORITHMS[name]()
    merged = merged_algorithm(name, lambda base: get_algorithm(base, plugins))
    if merged is not None:
        return merged
    if name.startswith(_VARIANT_PREFIX):
        return ApfOpaqueGrid.parse(name)
    if plugins and name in plugins:
        return plugins[name]()
    loaded = f", or the plug-ins loaded: {', '.join(sorted(plugins))}" if plugins else ""
    raise ValueError(
        f"unknown algorithm {name[:80]!r}: not built in (choose one of {', '.join(ALGORITHMS)}, or "
        f"{_VARIANT_PREFIX}R1,R2, or any of them{MARKER}a=b){loaded})"
    )


def _import_from_here(module: str) -> ModuleType:
    """Import ``module`` as ``python -m`` would: the current folder first (the ``apf-viz`` script's
    own folder is what Python puts first, not the user's), then the usual places."""
    here = os.getcwd()
    added = here not in sys.path
    if added:
        sys.path.insert(0, here)
    try:
        return importlib.import_module(module)
    finally:
        if added:
            sys.path.remove(here)


def load_plugin(spec: str) -> dict[str, Factory]:
    """Import ``package.module:Name`` (a class or factory taking no arguments) for the command line.

    Returns the plug-in under its spec and under the algorithm's own ``name``, for
    :func:`get_algorithm`'s ``plugins``. Never call this with a name read from a file or a browser."""
    module, sep, attr = spec.partition(":")
    if not sep or not module or not attr:
        raise ValueError(f"cannot load algorithm {spec!r}: a plug-in is named package.module:Name")
    try:
        factory = getattr(_import_from_here(module), attr)
    except ModuleNotFoundError as e:
        raise ValueError(
            f"cannot load algorithm {spec!r}: {e} (a plug-in's module is found in the current folder, "
            f"as {module.split('.')[0]}.py or a package of that name, or wherever Python finds installed "
            "modules)"
        ) from None
    except (ImportError, AttributeError) as e:
        raise ValueError(f"cannot load algorithm {spec!r}: {e}") from None
    if not (inspect.isclass(factory) or inspect.isfunction(factory)):  # not os:abort, not a builtin
        raise ValueError(f"{spec!r} is not an algorithm class or factory function")
    if inspect.isfunction(factory) and any(
        p.default is p.empty and p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)
        for p in inspect.signature(factory).parameters.values()
    ):
        raise ValueError(f"{spec!r} needs arguments: an algorithm factory takes none")
    try:
        algo = factory()
    except Exception as e:  # the plug-in's own constructor failed: say so in one line
        raise ValueError(f"cannot load algorithm {spec!r}: {type(e).__name__}: {e}") from None
    if not isinstance(algo, Algorithm):
        raise ValueError(f"{spec!r} is not an algorithm (needs name, lights and decide())")
    made = cast(Factory, factory)  # checked above: a class or function that made an Algorithm
    return {spec: made, str(algo.name): made}


def algorithm_from_command_line(name: str) -> tuple[Algorithm, dict[str, Factory]]:
    """What ``--algorithm`` names: a registry name, or a plug-in ``module:Name`` that is imported here.
    Returns the algorithm and the plug-ins loaded (empty for a registry name)."""
    if ":" in name and name not in ALGORITHMS and not name.startswith(_VARIANT_PREFIX):
        plugins = load_plugin(name)
        return get_algorithm(name, plugins), plugins
    return get_algorithm(name), {}
