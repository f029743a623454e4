"""Soak: thousands of random solvable starts through the paper's algorithm under every scheduler.

Run: python benchmarks/soak.py [--starts 2000] [--max-k 14] [--algorithm apf-opaque-grid] [--lc-atomic]
Prints every failure (start, pattern, scheduler, seed) and a summary; exit 1 if anything failed.
"""

from __future__ import annotations

import argparse
import random
import sys
import time

from apf_viz.algorithms import get_algorithm
from apf_viz.algorithms.apf_opaque_grid.audit import audit_run, random_pattern, random_solvable_start
from apf_viz.core.engine import Engine

SCHEDULERS = ("async", "stale-first", "ssync", "fsync", "round-robin")


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--starts", type=int, default=2000)
    ap.add_argument("--max-k", type=int, default=14)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--algorithm", default="apf-opaque-grid")
    ap.add_argument("--lc-atomic", action="store_true")
    ap.add_argument("--schedulers", default=",".join(SCHEDULERS))
    args = ap.parse_args()
    rng = random.Random(args.seed)
    failures = 0
    runs = 0
    t0 = time.perf_counter()
    for i in range(args.starts):
        k = rng.randint(1, args.max_k)
        start = random_solvable_start(k, rng)
        pattern = random_pattern(k, rng)
        y_up = [rng.random() < 0.5 for _ in range(k)]
        for sched in args.schedulers.split(","):
            seed = rng.randrange(1 << 30)
            engine = Engine(
                start,
                pattern,
                get_algorithm(args.algorithm),
                y_up=y_up,
                max_events=200_000,
                light_semantics="lc-atomic" if args.lc_atomic else "compute",
            )
            audit = audit_run(engine, sched, seed)
            runs += 1
            if not audit.ok:
                failures += 1
                print(
                    f"FAIL start={start} y_up={y_up} pattern={pattern} scheduler={sched} seed={seed}: "
                    f"{'; '.join(audit.problems)}",
                    flush=True,
                )
        if (i + 1) % 100 == 0:
            print(
                f"{i + 1} starts, {runs} runs, {failures} failures, {time.perf_counter() - t0:.0f}s",
                file=sys.stderr,
                flush=True,
            )
    print(f"{runs} runs, {failures} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
