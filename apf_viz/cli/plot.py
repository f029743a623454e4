"""``apf-viz plot``: plots of a sweep or of the light lab."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from apf_viz.cli.common import need_extra
from apf_viz.core.files import check_readable

NAME = "plot"
HELP = (
    "plot a sweep's results (PNG): moves vs k·D, failure rates, events per move; or a lights table's "
    "matrix of merges"
)


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("results", type=Path, help="the results file of apf-viz sweep or apf-viz lights")
    p.add_argument(
        "--out", type=Path, default=Path("plots"), help="folder for the PNGs (its path said first)"
    )


def run(args: argparse.Namespace) -> int:
    need_extra("plot", ["matplotlib", "pyarrow"])
    from apf_viz import charts, lights
    from apf_viz import sweeps as sweep

    check_readable(args.results)  # missing, a folder or a FIFO: one line
    if args.results.suffix == ".parquet" and lights.is_lights_table(args.results):
        table = lights.read_lights(args.results)
        _say_where(args.out)  # once the table is read: a bad one is refused in its one line
        written = [charts.plot_lights(table, args.out)]
    else:
        rows = sweep.read_results(args.results)
        _say_where(args.out)
        written = charts.plot(rows, args.out)
    for path in written:
        print(path)
    return 0


def _say_where(out: Path) -> None:
    print(f"apf-viz plot: writing PNGs into {out}/", file=sys.stderr, flush=True)
