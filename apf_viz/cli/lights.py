"""``apf-viz lights``: the light-budget lab."""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from apf_viz.algorithms import DEFAULT_ALGORITHM
from apf_viz.cli.common import cluster, fail, need_extra, workers

NAME = "lights"
HELP = "which lights could be one colour? every merge of two, explored (apf-viz docs lights)"
OUTPUTS = ("out",)
"""The options naming files this command writes (never one of its inputs)."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--algorithm", default=DEFAULT_ALGORITHM, help="the algorithm whose lights are merged")
    p.add_argument(
        "--ks",
        default="1-5",
        help="robots the explorer covers: 1–3 every start of a 4×4 box, 4–5 the stated starts",
    )
    p.add_argument("--merges", help="only these merges, e.g. leader1=decider,off=call (default: every one)")
    p.add_argument(
        "--random",
        type=int,
        default=0,
        help="random runs (half of k = 6–12 random robots, half on the Demo starts) for each merge the "
        "explorer could not break",
    )
    p.add_argument(
        "--out",
        required=True,
        type=Path,
        help="the verdicts table (.parquet), resumed if there; beside it NAME-base.json (stage 0), "
        "NAME-traces/ (counterexamples) and, with --random, NAME-random.parquet",
    )
    p.add_argument("--traces", type=Path, help="counterexample traces here (default: OUT's name + -traces)")
    p.add_argument("--workers", type=workers, help="local worker processes (default: one per core)")
    p.add_argument(
        "--cluster", type=cluster, help="address of a running Dask scheduler, e.g. tcp://host:8786"
    )


def run(args: argparse.Namespace) -> int:
    need_extra("lights", ["dask", "distributed", "pyarrow"])
    from apf_viz import lights

    if args.out.suffix != ".parquet":
        fail(f"--out {args.out}: the lab writes a .parquet table")
    if not 0 <= args.random <= lights.MAX_RANDOM_RUNS:
        fail(f"--random {args.random:,}: a number of runs per merge, from 0 to {lights.MAX_RANDOM_RUNS:,}")
    chosen = lights.merges(args.algorithm, args.merges)
    ks = lights.parse_ks(args.ks)
    t0 = time.perf_counter()
    rows = lights.run_lab(  # Ctrl+C keeps what finished (cli/__init__.py's main: exit 130)
        chosen,
        ks,
        args.out,
        random_runs=args.random,
        traces=args.traces,
        workers=args.workers,
        cluster=args.cluster,
        progress=lights.report_progress,
        plan=_plan(args, len(chosen), ks),
    )
    names = {m.name for m in chosen}
    print(lights.summary([r for r in rows if r["merge"] in names and r["ks"] == lights.ks_label(ks)]))
    beside = [
        (args.out.with_name(args.out.stem + "-base.json"), "stage 0's verdicts on the base algorithm"),
        (args.traces or args.out.with_name(args.out.stem + "-traces"), "counterexample traces"),
        (args.out.with_name(args.out.stem + "-random.parquet"), "the random runs"),
    ]
    written = "; ".join(f"{path} ({what})" for path, what in beside if path.exists())
    seconds = time.perf_counter() - t0
    print(f"apf-viz lights: {args.out}, and beside it {written}; {seconds:.0f} s", file=sys.stderr)
    return 0


def _plan(args: argparse.Namespace, merges: int, ks) -> str:
    """The first line, before any work: what the lab does, every file it writes, and how long stage 0
    will take when an earlier run kept it (else it is timed, and the merges' bound said after it)."""
    from apf_viz import lights

    base = lights.base_path(args.out)
    traces = args.traces or args.out.with_name(args.out.stem + "-traces")
    files = [f"{base} (stage 0)", f"{traces}/ (counterexamples)"]
    if args.random:
        files.append(f"{lights.random_path(args.out)} (the random runs)")
    starts = lights.starts_for(ks)
    kept = lights.kept_base(base, args.algorithm)
    stage0 = (
        "stage 0 kept from an earlier run"
        if all(name in kept for name, _ in starts)
        else f"stage 0 first: the base algorithm on {len(starts)} starts, timed, then the merges' bound said"
    )
    return (
        f"apf-viz lights: {merges} merges of {args.algorithm}'s lights, k {lights.ks_label(ks)}; writes "
        f"{args.out} and beside it {', '.join(files)}; {stage0}"
    )
