"""Explorer speed: states per second on a k = 4 start (target ≥ 20,000/s) and how the state count grows
with k (ASYNC, all y-axes up, the default algorithm), with and without the partial-order reduction.
Run: python benchmarks/bench_explorer.py"""

from __future__ import annotations

from apf_viz.algorithms import get_algorithm
from apf_viz.explore.explorer import Explorer

STARTS = {
    1: [(0, 0)],
    2: [(0, 0), (1, 1)],
    3: [(0, 0), (2, 1), (3, -1)],
    4: [(0, 0), (0, 1), (0, 2), (0, 4)],
    5: [(0, 0), (0, 2), (1, 0), (1, 1), (1, 2)],
}


def main() -> None:
    algorithm = get_algorithm("apf-opaque-grid")
    print("| k | start | reduction | verdict | states | transitions | time | states/s |")
    print("|---:|---|---|---|---:|---:|---:|---:|")
    for k, start in STARTS.items():
        for reduction in (False, True):
            r = Explorer(
                algorithm,
                start,
                [(i, 0) for i in range(k)],
                [True] * k,
                max_states=3_000_000,
                reduction=reduction,
            ).run()
            rate = f"{r.states / r.seconds:,.0f}" if r.seconds > 1e-3 else "—"
            print(
                f"| {k} | {start} | {'yes' if reduction else 'no'} | {r.verdict} | {r.states:,} | "
                f"{r.transitions:,} | {r.seconds:.1f} s | {rate} |",
                flush=True,
            )


if __name__ == "__main__":
    main()
