"""``apf-viz plot``: plots of a sweep or of the light lab."""

from __future__ import annotations

import argparse
from pathlib import Path

from apf_viz.cli.common import fail, need_extra

NAME = "plot"
HELP = (
    "plot a sweep's results (PNG): moves vs k·D, failure rates, events per move; or a lights table's "
    "matrix of merges"
)


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("results", type=Path, help="the results file of apf-viz sweep or apf-viz lights")
    p.add_argument("--out", type=Path, default=Path("plots"), help="folder for the PNGs")


def run(args: argparse.Namespace) -> int:
    need_extra("plot", ["matplotlib", "pyarrow"])
    from apf_viz import lights, plot, sweep

    if not args.results.is_file():
        fail(f"{args.results}: no such file")
    if args.results.suffix == ".parquet" and lights.is_lights_table(args.results):
        written = [plot.plot_lights(lights.read_lights(args.results), args.out)]
    else:
        written = plot.plot(sweep.read_results(args.results), args.out)
    for path in written:
        print(path)
    return 0
