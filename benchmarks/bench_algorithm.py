"""The paper's O(kD) bound, measured: moves / (k·D) and events under ASYNC for growing k.

D = max(m, n, M, N, k) as in the paper (m, n: height and width of the start's enclosing rectangle;
M, N: the pattern's). Run: python benchmarks/bench_algorithm.py [--ks 5,10,20,40,80,100] [--seeds 3]
"""

from __future__ import annotations

import argparse
import random
import time

from apf_viz.algorithms import get_algorithm
from apf_viz.algorithms.apf_opaque_grid.audit import audit_run, random_pattern, random_solvable_start
from apf_viz.core.engine import Engine


def extent(points) -> tuple[int, int]:
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    return max(xs) - min(xs) + 1, max(ys) - min(ys) + 1


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--ks", default="5,10,20,40,80,100")
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--scheduler", default="async")
    args = ap.parse_args()
    print(f"| k | D | moves | moves/(k·D) | events | wall time ({args.scheduler}) |")
    print("|---:|---:|---:|---:|---:|---:|")
    for k in map(int, args.ks.split(",")):
        for seed in range(args.seeds):
            rng = random.Random(k * 1000 + seed)
            start = random_solvable_start(k, rng)
            pattern = random_pattern(k, rng)
            d = max(*extent(start), *extent(pattern), k)
            y_up = [rng.random() < 0.5 for _ in range(k)]
            engine = Engine(
                start, pattern, get_algorithm("apf-opaque-grid"), y_up=y_up, max_events=20_000_000
            )
            t0 = time.perf_counter()
            audit = audit_run(engine, args.scheduler, seed)
            dt = time.perf_counter() - t0
            assert audit.ok, audit.problems
            print(
                f"| {k} | {d} | {audit.moves:,} | {audit.moves / (k * d):.3f} | {audit.events:,} "
                f"| {dt:.1f} s |",
                flush=True,
            )


if __name__ == "__main__":
    main()
