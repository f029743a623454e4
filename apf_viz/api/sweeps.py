"""Many runs from Python: :func:`sweep` runs the grid ``apf-viz sweep`` runs, on the same Dask driver (on
this machine's cores, or a cluster), and returns its table as a pandas DataFrame."""

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
from apf_viz.core.schedulers import DEFAULT_SCHEDULER

if TYPE_CHECKING:
    import pandas


def sweep(
    ks: Iterable[int] = (5, 10, 20),
    seeds: Iterable[int] = range(1, 11),
    *,
    schedulers: Iterable[str] = (DEFAULT_SCHEDULER,),
    algorithms: Iterable[str] = (DEFAULT_ALGORITHM,),
    light_semantics: Iterable[str] = ("compute",),
    starts: str | os.PathLike[str] | None = None,
    out: str | os.PathLike[str] | None = None,
    traces: str | os.PathLike[str] | None = None,
    workers: int | None = None,
    cluster: str | None = None,
    run_timeout: float | None = None,
    progress: bool = True,
) -> pandas.DataFrame:
    """Every run of the grid (each k, seed, scheduler, algorithm and light semantics; or each pair of
    ``starts``, a folder of ``NAME.robots.json`` + ``NAME.pattern.json``), one row each, with the columns
    ``apf-viz sweep`` writes (k, D, seed, scheduler, algorithm, outcome, moves, events, moves_per_kD, …).

    ``out``: also keep the table in this ``.parquet`` or ``.csv`` file, resumed if it exists (as the
    command's ``--out``); without it the table lives in a temporary file. ``workers``: local processes
    (default: one per core); ``cluster``: a running Dask scheduler's address instead. Needs the ``sweep``
    extra (Dask, pyarrow) and pandas (the ``notebook`` extra).

    >>> table = sweep(ks=[4], seeds=range(2), workers=1)
    >>> sorted(table.columns)[:3], len(table)
    (['D', 'algorithm', 'cycles'], 2)
    """
    pandas = pandas_for("sweep's table")
    ks, seeds = whole_numbers("ks", ks), whole_numbers("seeds", seeds, 0)
    from apf_viz import sweeps as driver

    cells = driver.grid(
        ks,
        seeds,
        list(schedulers),
        list(algorithms),
        list(light_semantics),
        Path(starts) if starts is not None else None,
    )
    with (
        tempfile.TemporaryDirectory(prefix="apf-viz-sweep-") as scratch,
        ProgressBar("apf-viz sweep", len(cells), "runs", progress) as bar,
    ):
        path = Path(out) if out is not None else Path(scratch) / "results.parquet"
        if path.suffix not in (".parquet", ".csv"):
            raise InputError(f"out {path}: write .parquet or .csv")
        with local_workers("sweep()", cluster):
            rows = driver.run_sweep(
                cells,
                path,
                traces=Path(traces) if traces is not None else None,
                workers=workers,
                cluster=cluster,
                progress=lambda p: bar.to(p.finished, f"{p.failed} not formed"),
                run_timeout=run_timeout,
            )
    return pandas.DataFrame(rows, columns=list(driver.COLUMNS))
