"""``apf-viz hunt``: the exhaustive check on many generated starts, into one table."""

from __future__ import annotations

import argparse
from pathlib import Path

from apf_viz.algorithms import DEFAULT_ALGORITHM
from apf_viz.cli.common import (
    cluster,
    fail,
    need_extra,
    positive,
    seed,
    stop_on_sigterm_as_on_ctrl_c,
    workers,
)
from apf_viz.explore.hunt_families import FAMILIES

NAME = "hunt"
HELP = "check every schedule of many generated starts, into one table (apf-viz docs verification)"
OUTPUTS = ("out", "counterexamples")
"""The options naming files this command writes (never one of its inputs)."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--ks", default="6-12", help="robot counts to draw from: a list and/or ranges, e.g. 6-40")
    p.add_argument("--count", type=positive, default=30, help="how many starts")
    p.add_argument("--seed", type=seed, default=1, help="the hunt's seed: the same seed, the same starts")
    p.add_argument(
        "--families",
        default=",".join(FAMILIES),
        help="comma-separated families of starts, taken in turn",
    )
    p.add_argument(
        "--flips", choices=("drawn", "all"), default="drawn",
        help="each start's own random y-axes, or every assignment of them (2^k searches a start)",
    )  # fmt: skip
    p.add_argument("--algorithm", default=DEFAULT_ALGORITHM, help="the algorithm checked (a registry name)")
    p.add_argument(
        "--max-states", type=positive, default=500_000,
        help="states one start may take; past it the start is 'budget' (nothing proved), not verified",
    )  # fmt: skip
    p.add_argument("--out", type=Path, required=True, help="hunt.parquet (resumed if present)")
    p.add_argument(
        "--counterexamples", type=Path,
        help="a folder for the traces of the failures found (default: beside --out, OUT-counterexamples)",
    )  # fmt: skip
    p.add_argument("--workers", type=workers, help="local worker processes (default: one per core)")
    p.add_argument("--cluster", type=cluster, help="address of a running Dask scheduler, tcp://host:8786")


def run(args: argparse.Namespace) -> int:
    need_extra("hunt", ["dask", "distributed", "pyarrow"])
    from apf_viz.algorithms import get_algorithm
    from apf_viz.explore.hunt import hunt_starts
    from apf_viz.sweeps import parse_range
    from apf_viz.sweeps.hunt_driver import report_hunt, run_hunt
    from apf_viz.sweeps.hunt_table import hunt_summary

    if args.out.suffix != ".parquet":
        fail(f"--out {args.out}: write .parquet")
    get_algorithm(args.algorithm)  # a name outside the registry: one line, before any work
    families = [f.strip() for f in args.families.split(",") if f.strip()]
    starts = hunt_starts(parse_range(args.ks, "--ks"), args.count, args.seed, families)
    folder = args.counterexamples or args.out.with_name(args.out.stem + "-counterexamples")
    stop_on_sigterm_as_on_ctrl_c()  # keeps the starts that finished
    rows = run_hunt(
        starts, args.out, algorithm=args.algorithm, max_states=args.max_states, counterexamples=folder,
        flips=args.flips,
        workers=args.workers, cluster=args.cluster, progress=report_hunt,
    )  # fmt: skip
    print(hunt_summary([r for r in rows if r["algorithm"] == args.algorithm]))
    failing = [
        r for r in rows if r["algorithm"] == args.algorithm and r["verdict"] not in ("verified", "budget")
    ]
    short = [r for r in rows if r["algorithm"] == args.algorithm and r["verdict"] == "budget"]
    if short:
        print(f"{len(short)} start(s) ran out of --max-states {args.max_states:,}: not verified")
    for r in failing[:10]:
        print(
            f"{r['verdict']}: {r['family']} k={r['k']} seed {r['seed']}: {r['detail']}; {r['counterexample']}"
        )
    return 1 if failing else 4 if short else 0
