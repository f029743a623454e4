"""`apf-viz sweep`: thousands of runs on Dask, one results table.

The grid of runs is the product of the lists (k × seed × scheduler × algorithm × light semantics), or of
the start/pattern pairs of a folder instead of (k, seed). Each run is a task on a Dask cluster: by
default a ``LocalCluster`` of one single-threaded worker process per core; ``--cluster ADDRESS`` submits
to an existing scheduler. Results are one row per run (Parquet, or CSV by the file's extension), written
atomically as runs finish; re-running the same command skips the runs already in the file; Ctrl+C keeps
what finished. A run whose worker dies is recorded as ``error`` with the message, and the sweep goes on.

Reproducible starts (docs/SWEEPS.md): for (k, seed), the box is s × s with s = max(3, ⌊√(3k)⌋ + 1); the
robots are ``random_robots(k, s, s, 2·seed)`` (redrawn until solvable, as ``apf-viz random-robots``), the
pattern ``random_pattern(k, s, s, 2·seed + 1)``, the flips ``random_y_up(k, seed)``.
"""

from apf_viz.sweeps.cells import COLUMNS as COLUMNS
from apf_viz.sweeps.cells import KEY as KEY
from apf_viz.sweeps.cells import MAX_K as MAX_K
from apf_viz.sweeps.cells import MAX_RUNS as MAX_RUNS
from apf_viz.sweeps.cells import MAX_VALUES as MAX_VALUES
from apf_viz.sweeps.cells import Cell as Cell
from apf_viz.sweeps.cells import generated_start as generated_start
from apf_viz.sweeps.cells import grid as grid
from apf_viz.sweeps.cells import parse_range as parse_range
from apf_viz.sweeps.cells import row as row
from apf_viz.sweeps.cells import run_cell as run_cell
from apf_viz.sweeps.cells import start_pairs as start_pairs
from apf_viz.sweeps.driver import Progress as Progress
from apf_viz.sweeps.driver import by_the_second as by_the_second
from apf_viz.sweeps.driver import cost as cost
from apf_viz.sweeps.driver import dask_client as dask_client
from apf_viz.sweeps.driver import duration as duration
from apf_viz.sweeps.driver import report_progress as report_progress
from apf_viz.sweeps.driver import run_sweep as run_sweep
from apf_viz.sweeps.driver import shut_down as shut_down
from apf_viz.sweeps.driver import summary as summary
from apf_viz.sweeps.driver import usable_cores as usable_cores
from apf_viz.sweeps.results import read_results as read_results
from apf_viz.sweeps.results import write_results as write_results

__all__ = [
    "COLUMNS",
    "KEY",
    "MAX_K",
    "MAX_RUNS",
    "MAX_VALUES",
    "Cell",
    "Progress",
    "by_the_second",
    "cost",
    "dask_client",
    "duration",
    "generated_start",
    "grid",
    "parse_range",
    "read_results",
    "report_progress",
    "row",
    "run_cell",
    "run_sweep",
    "shut_down",
    "start_pairs",
    "summary",
    "usable_cores",
    "write_results",
]
