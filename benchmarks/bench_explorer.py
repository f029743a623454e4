"""Explorer speed: states per second and bytes per state on k = 2–5 starts (ASYNC, all y-axes up, the
default algorithm), with and without the partial-order reduction; then the light lab's kind of search,
every flip assignment of a k = 4–5 start (`check`, which shares decisions across flip assignments).
Bytes per state: the peak of traced allocations during a second, traced run (tracemalloc slows it, so
the time is from the first) divided by the states; for every flip assignment, the peak (one search at a
time is held, and the decisions they share).
Run: python benchmarks/bench_explorer.py"""

from __future__ import annotations

import time
import tracemalloc

from apf_viz.algorithms import get_algorithm
from apf_viz.explore.check import all_flips, check
from apf_viz.explore.explorer import Explorer

STARTS = {
    1: [(0, 0)],
    2: [(0, 0), (1, 1)],
    3: [(0, 0), (2, 1), (3, -1)],
    4: [(0, 0), (0, 1), (0, 2), (0, 4)],
    5: [(0, 0), (0, 2), (1, 0), (1, 1), (1, 2)],
}
ALL_FLIPS = {
    "C2": [(0, 0), (0, 2), (1, 0), (1, 3)],
    "C6": [(0, 0), (0, 2), (1, 0), (1, 2), (2, 5)],
    "symmetric, robots on the axis": [(0, 0), (0, 1), (0, 3), (0, 4), (1, 2)],
}


def traced_peak(run) -> int:
    tracemalloc.start()
    try:
        run()
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def main() -> None:
    algorithm = get_algorithm("apf-opaque-grid")
    print("| k | start | reduction | verdict | states | transitions | time | states/s | bytes/state |")
    print("|---:|---|---|---|---:|---:|---:|---:|---:|")
    for k, start in STARTS.items():
        for reduction in (False, True):

            def run(start=start, k=k, reduction=reduction):
                return Explorer(
                    algorithm,
                    start,
                    [(i, 0) for i in range(k)],
                    [True] * k,
                    max_states=3_000_000,
                    reduction=reduction,
                ).run()

            r = run()
            rate = f"{r.states / r.seconds:,.0f}" if r.seconds > 1e-3 else "—"
            per = f"{traced_peak(run) / r.states:,.0f}" if r.states > 1000 else "—"
            print(
                f"| {k} | {start} | {'yes' if reduction else 'no'} | {r.verdict} | {r.states:,} | "
                f"{r.transitions:,} | {r.seconds:.1f} s | {rate} | {per} |",
                flush=True,
            )
    print()
    print("| start (every flip assignment, reduction) | verdict | states | time | states/s | peak |")
    print("|---|---|---:|---:|---:|---:|")
    for name, start in ALL_FLIPS.items():
        k = len(start)

        def run_all(start=start, k=k):
            return check(
                algorithm, start, [(i, 0) for i in range(k)], all_flips(k), "async", 5_000_000, False
            )[0]

        t0 = time.perf_counter()
        r = run_all()
        seconds = time.perf_counter() - t0
        peak = traced_peak(run_all) / 2**20
        print(
            f"| {name} {start} | {r.verdict} | {r.states:,} | {seconds:.1f} s | {r.states / seconds:,.0f} | "
            f"{peak:.1f} MiB |",
            flush=True,
        )


if __name__ == "__main__":
    main()
