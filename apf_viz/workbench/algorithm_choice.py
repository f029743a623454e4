"""The algorithm a run uses, as a person picks it: the built-in names, and "two lights as one colour"
(a light merge, algorithms/merged_lights.py) as words. The UI offers these without importing any
algorithm (docs/ARCHITECTURE.md)."""

from __future__ import annotations

from collections.abc import Iterable

from apf_viz.algorithms import ALGORITHMS
from apf_viz.algorithms.merged_lights import MergedLights, merged_name, split_name
from apf_viz.core.algorithm import Algorithm

__all__ = ["NO_MERGE", "algorithm_names", "light_merges", "merge_of", "with_merge"]

NO_MERGE = "—"  # the choice of no merge: every light its own colour


def algorithm_names(current: str, plugins: Iterable[str] = ()) -> tuple[str, ...]:
    """The built-in algorithms and the run's plug-ins named by the registry (not ``module:Name``), with
    ``current`` last if it is none of them (a variant).

    Args:
        current: the run's algorithm name.
        plugins: the names of the plug-ins loaded for the run.

    Returns:
        The names, the registry's order first.
    """
    names = [*ALGORITHMS, *(n for n in plugins if ":" not in n)]
    return tuple(names if current in names else [*names, current])


def light_merges(algorithm: Algorithm) -> tuple[str, ...]:
    """:data:`NO_MERGE` and "b shown as a" for every ordered pair of the unmerged algorithm's lights.

    Args:
        algorithm: the run's algorithm, merged or not.

    Returns:
        The choices, as a person reads them.
    """
    lights = (algorithm.base if isinstance(algorithm, MergedLights) else algorithm).lights
    return (NO_MERGE, *(f"{b} shown as {a}" for a in lights for b in lights if a != b))


def merge_of(name: str) -> str:
    """The merge an algorithm name asks for, as :func:`light_merges` words it (one merge only).

    Args:
        name: an algorithm name, e.g. ``apf-opaque-grid+merge(leader1=decider)``.

    Returns:
        "decider shown as leader1", or :data:`NO_MERGE`.
    """
    parts = split_name(name)
    if parts is None or len(parts[1]) != 1:
        return NO_MERGE
    (a, b), *_ = parts[1]
    return f"{b} shown as {a}"


def with_merge(name: str, choice: str) -> str:
    """The algorithm name of ``name``'s base with the merge ``choice`` (:data:`NO_MERGE`: none).

    Args:
        name: the run's algorithm name, merged or not.
        choice: one of :func:`light_merges`.

    Returns:
        The name to switch to.
    """
    parts = split_name(name)
    base = parts[0] if parts else name
    if choice == NO_MERGE:
        return base
    b, a = choice.split(" shown as ")
    return merged_name(base, [(a, b)])
