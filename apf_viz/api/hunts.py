"""A hunt from Python: :func:`hunt` checks every schedule of many generated starts, as ``apf-viz hunt``
does (the same starts for the same seed, the same Dask driver), and returns its table as a DataFrame."""

from __future__ import annotations

import os
import tempfile
from collections.abc import Iterable
from pathlib import Path
from typing import TYPE_CHECKING

from apf_viz.algorithms import DEFAULT_ALGORITHM
from apf_viz.api.inputs import whole_numbers
from apf_viz.api.progress_bars import ProgressBar
from apf_viz.api.tables import pandas_for
from apf_viz.api.workers import local_workers
from apf_viz.core.formats import InputError

if TYPE_CHECKING:
    import pandas


def hunt(
    ks: Iterable[int] = range(6, 13),
    count: int = 30,
    *,
    seed: int = 1,
    families: Iterable[str] | None = None,
    algorithm: str = DEFAULT_ALGORITHM,
    flips: str = "drawn",
    max_states: int = 500_000,
    out: str | os.PathLike[str] | None = None,
    counterexamples: str | os.PathLike[str] | None = None,
    workers: int | None = None,
    cluster: str | None = None,
    progress: bool = True,
) -> pandas.DataFrame:
    """``count`` generated starts (k drawn from ``ks``, the ``families`` in turn: all by default), each
    searched exhaustively under ASYNC; one row per start with ``apf-viz hunt``'s columns (family, k, seed,
    D, verdict, states, seconds, counterexample, …). A start past ``max_states`` is verdict "budget":
    nothing proved. ``flips="all"``: every assignment of the robots' y-axes (2^k searches a start).
    ``out``: keep the table in this ``.parquet`` file, resumed if it exists. ``progress``: a bar with
    the starts done and an ETA.

    >>> table = hunt(ks=[4], count=2, workers=1)
    >>> sorted(set(table["verdict"]))
    ['verified']
    """
    from apf_viz.explore.hunt import COLUMNS, hunt_starts
    from apf_viz.explore.hunt_families import FAMILIES
    from apf_viz.sweeps.hunt_driver import run_hunt

    pandas = pandas_for("hunt's table")
    _check_arguments(count, max_states, algorithm, flips)
    chosen = list(FAMILIES) if families is None else list(families)
    try:
        starts = hunt_starts(whole_numbers("ks", ks), count, seed, chosen)
    except ValueError as e:
        raise InputError(str(e)) from None
    with tempfile.TemporaryDirectory(prefix="apf-viz-hunt-") as scratch:
        path = Path(out) if out is not None else Path(scratch) / "hunt.parquet"
        if path.suffix != ".parquet":
            raise InputError(f"out {path}: write .parquet")
        folder = path.with_name(path.stem + "-counterexamples")
        folder = Path(counterexamples) if counterexamples is not None else folder
        with (
            ProgressBar("apf-viz hunt", len(starts), "starts", progress) as bar,
            local_workers("hunt()", cluster),
        ):
            rows = run_hunt(
                starts, path, algorithm=algorithm, max_states=max_states, counterexamples=folder,
                flips=flips, workers=workers, cluster=cluster,
                progress=lambda p: bar.to(p.finished, f"{p.failures} failing, {p.budget} out of budget"),
            )  # fmt: skip
        mine = [r for r in rows if r["algorithm"] == algorithm and r["flips"] == flips]
        table = pandas.DataFrame(mine, columns=list(COLUMNS))
    return table


def _check_arguments(count: object, max_states: object, algorithm: str, flips: str) -> None:
    """Each argument a hunt takes, refused in one line before any work."""
    from apf_viz.algorithms import get_algorithm

    for name, value in (("count", count), ("max_states", max_states)):
        if not isinstance(value, int) or isinstance(value, bool) or value < 1:
            raise InputError(f"{name} must be a positive integer, not {value!r}")
    get_algorithm(algorithm)
    if flips not in ("drawn", "all"):
        raise InputError(f"flips must be 'drawn' or 'all', not {flips!r}")
