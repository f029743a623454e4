"""``apf-viz sweep``: a grid of runs on Dask into one results table."""

from __future__ import annotations

import argparse
from dataclasses import replace
from pathlib import Path

from apf_viz.algorithms import DEFAULT_ALGORITHM
from apf_viz.cli.common import cluster, fail, need_extra, positive, positive_seconds, workers
from apf_viz.core.files import check_writable
from apf_viz.core.schedulers import DEFAULT_SCHEDULER
from apf_viz.sweeps.cells import Cell

NAME = "sweep"
HELP = "run a grid of runs on Dask into one results table (apf-viz docs sweeps)"
OUTPUTS = ("out",)
"""The options naming files this command writes (never one of its inputs)."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--ks", default="5,10,20", help="robot counts: a list and/or ranges, e.g. 5,10,20 or 3-6")
    p.add_argument("--seeds", default="1-10", help="seeds: e.g. 1-50 (each seed gives its own start)")
    p.add_argument("--schedulers", default=DEFAULT_SCHEDULER, help="comma-separated schedulers")
    p.add_argument("--algorithms", default=DEFAULT_ALGORITHM, help="comma-separated algorithm names")
    p.add_argument("--light-semantics", default="compute", help="comma-separated: compute, lc-atomic")
    p.add_argument(
        "--starts", type=Path, help="a folder of NAME.robots.json + NAME.pattern.json pairs instead of --ks"
    )
    p.add_argument(
        "--out", type=Path, required=True, help="results.parquet or results.csv (resumed if present)"
    )
    p.add_argument("--traces", type=Path, help="write a trace of every run that did not form here")
    p.add_argument("--workers", type=workers, help="local worker processes (default: one per core)")
    p.add_argument(
        "--cluster", type=cluster, help="address of a running Dask scheduler, e.g. tcp://host:8786"
    )
    p.add_argument(
        "--search-budget", type=positive, default=Cell.search_budget,
        help="schedules the searched adversary tries in each run of the scheduler worst-found, beside the "
        "built-ins' 100 runs (4: beams of width 64 to 512; docs/ADVERSARY.md)",
    )  # fmt: skip
    p.add_argument(
        "--run-timeout",
        type=positive_seconds,
        help="seconds one run may take; a run past it is recorded as outcome 'timeout' with its counts "
        "so far, and the sweep goes on (default: no limit)",
    )


def run(args: argparse.Namespace) -> int:
    need_extra("sweep", ["dask", "distributed", "pyarrow"])
    from apf_viz import sweeps as sweep

    if args.out.suffix not in (".parquet", ".csv"):
        fail(f"--out {args.out}: write .parquet or .csv")
    cells = sweep.grid(
        sweep.parse_range(args.ks, "--ks"),
        sweep.parse_range(args.seeds, "--seeds"),
        [s.strip() for s in args.schedulers.split(",")],
        [a.strip() for a in args.algorithms.split(",")],
        [s.strip() for s in args.light_semantics.split(",")],
        args.starts,
    )
    cells = [replace(c, search_budget=args.search_budget) for c in cells]
    check_writable(args.out)
    rows = sweep.run_sweep(  # Ctrl+C keeps what finished (cli/__init__.py's main: exit 130)
        cells,
        args.out,
        traces=args.traces,
        workers=args.workers,
        cluster=args.cluster,
        progress=sweep.report_progress,
        run_timeout=args.run_timeout,
    )
    print(sweep.summary(rows))
    return 0
