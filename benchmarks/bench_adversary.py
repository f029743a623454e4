"""The searched adversary's throughput (apf-viz adversary, explore/adversary.py) on generated starts
(``sweeps.cells.generated_start``) of k = 10 and k = 30: the beam over the adversary's choices
(explore/beam.py, width 64: its time and states a second), then schedules tried a second by the
variants' search (each a whole run of the engine to FORMED), here on one core and, with
``--cluster-workers N``, on a Dask LocalCluster of N worker processes (the ``--cluster`` path); and what
the search found against the built-ins.
Run: python benchmarks/bench_adversary.py [--ks 10,30] [--budget 60] [--cluster-workers 2]"""

from __future__ import annotations

import argparse
import time

from apf_viz.explore.adversary import Problem, search
from apf_viz.explore.beam import beam
from apf_viz.sweeps.cells import generated_start


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--ks", default="10,30")
    ap.add_argument("--budget", type=int, default=60)
    ap.add_argument("--seed", type=int, default=1, help="the generated start's")
    ap.add_argument("--cluster-workers", type=int, default=0, help="also on a LocalCluster of N processes")
    args = ap.parse_args()
    print("| k | beam (width 64): seconds, states/s, moves | schedules/s, one core | on the cluster | "
          "built-ins' most | found |")  # fmt: skip
    print("|---:|---:|---:|---:|---:|---:|")
    for k in (int(x) for x in args.ks.split(",")):
        robots, pattern, y_up = generated_start(k, args.seed)
        problem = Problem(
            "apf-opaque-grid", tuple(map(tuple, robots)), tuple(map(tuple, pattern)), tuple(y_up), "moves"
        )
        b = beam(problem.algorithm, robots, pattern, y_up, "moves", 64)
        here = search(problem, args.budget, seed=0, width=0)
        there = "–"
        if args.cluster_workers:
            there = f"{rate_on_cluster(problem, args.budget, args.cluster_workers):.1f}"
        print(
            f"| {k} | {b.seconds:.1f}, {b.states / b.seconds:,.0f}, {b.value} "
            f"| {(here.bar_runs + here.evaluations) / here.seconds:.1f} | {there} | {here.bar.value} "
            f"| {max(here.best.value or 0, b.value or 0)} |",
            flush=True,
        )


def rate_on_cluster(problem: Problem, budget: int, workers: int) -> float:
    """Schedules a second of the same search with each batch tried on a LocalCluster (its start-up not
    counted: a cluster serves many searches)."""
    from dask.distributed import LocalCluster

    from apf_viz.cli.adversary import on_cluster

    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None) as c:
        evaluator, close = on_cluster(c.scheduler_address)
        try:
            t0 = time.perf_counter()
            found = search(problem, budget, seed=0, evaluator=evaluator, width=0)
            return (found.bar_runs + found.evaluations) / (time.perf_counter() - t0)
        finally:
            close()


if __name__ == "__main__":
    main()
