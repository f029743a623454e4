"""A sweep's figures from Python: :func:`plot` draws what ``apf-viz plot`` draws from a sweep's table."""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from apf_viz.core.formats import InputError


def plot(table: Any, out: str | os.PathLike[str] = "plots") -> list[Path]:
    """The PNGs ``apf-viz plot`` writes (moves against k·D, failure rates, time per move) into the
    folder ``out``, from ``table``: :func:`~apf_viz.api.sweeps.sweep`'s DataFrame, its rows as dicts, or a
    results file (``.parquet`` or ``.csv``; the light lab's table gives its matrix of merges). Returns the
    files written. Needs the ``sweep`` extra (matplotlib)."""
    from apf_viz import charts

    folder = Path(out)
    if folder.exists() and not folder.is_dir():
        raise InputError(f"out {out}: is a file, not a folder for the PNGs")
    if isinstance(table, str | os.PathLike) and Path(table).suffix == ".parquet":
        from apf_viz import lights

        if lights.is_lights_table(Path(table)):  # the light lab's table: its matrix of merges
            return [charts.plot_lights(lights.read_lights(Path(table)), folder)]
    return charts.plot(_rows(table), folder)


def _rows(table: Any) -> list[dict[str, Any]]:
    if isinstance(table, str | os.PathLike):
        from apf_viz.core.files import check_readable
        from apf_viz.sweeps.results import read_results

        check_readable(Path(table))
        return read_results(Path(table))
    if hasattr(table, "to_dict") and hasattr(table, "columns"):  # a pandas DataFrame
        return list(table.to_dict("records"))
    if isinstance(table, Sequence) and all(isinstance(row, dict) for row in table):
        return list(table)
    raise InputError(
        f"table {type(table).__name__}: sweep()'s DataFrame, its rows as dicts, or a results file"
    )
