"""A run function for the sweep tests that kills its worker process on one cell (a crash, not an
exception), and runs every other cell normally. Module level, so that Dask workers can import it."""

from __future__ import annotations

import os

from apf_viz.sweep import Cell, run_cell


def crash_on_k4_seed2(cell: Cell, traces: str | None) -> dict:
    if cell.k == 4 and cell.seed == 2:
        os._exit(13)  # the worker dies mid-task
    return run_cell(cell, traces)
