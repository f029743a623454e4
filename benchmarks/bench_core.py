"""Core benchmarks: Look time against the naive lattice walk, and engine events per second.

Run: python benchmarks/bench_core.py   (prints a Markdown table; not part of the test suite)
"""

from __future__ import annotations

import random
import time
from math import gcd

import numpy as np

from apf_viz.algorithms.examples import CompactLeft
from apf_viz.core.engine import Engine
from apf_viz.core.grid import visible_from, visible_from_naive
from apf_viz.core.run import advance
from apf_viz.core.schedulers import make_scheduler


def random_points(k: int, seed: int = 1, density: float = 0.25) -> list[tuple[int, int]]:
    """k distinct random points in a square box with this fraction of its points occupied."""
    side = int((k / density) ** 0.5) + 1
    rng = random.Random(seed)
    cells = rng.sample(range(side * side), k)
    return [(c % side, c // side) for c in cells]


def visible_by_lattice_scan(points: list[tuple[int, int]], i: int) -> list[int]:
    """The naive Look: march from the robot along every primitive direction through every lattice point
    of the configuration's bounding box, taking the first robot met. O(area), whatever k is."""
    index = {p: j for j, p in enumerate(points)}
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    x0, y0 = points[i]
    lo_x, hi_x, lo_y, hi_y = min(xs), max(xs), min(ys), max(ys)
    seen = []
    for dx in range(lo_x - x0, hi_x - x0 + 1):
        for dy in range(lo_y - y0, hi_y - y0 + 1):
            if (dx, dy) == (0, 0) or gcd(abs(dx), abs(dy)) != 1:
                continue
            x, y = x0 + dx, y0 + dy
            while lo_x <= x <= hi_x and lo_y <= y <= hi_y:
                if (x, y) in index:
                    seen.append(index[(x, y)])
                    break
                x, y = x + dx, y + dy
    return sorted(seen)


def per_call(fn, budget_s: float = 1.0, max_calls: int = 2000) -> float:
    calls, start = 0, time.perf_counter()
    while calls < max_calls and (calls < 3 or time.perf_counter() - start < budget_s):
        fn(calls)
        calls += 1
    return (time.perf_counter() - start) / calls


def bench_look(density: float) -> list[str]:
    rows = [
        f"Occupied fraction of the box: {density}",
        "",
        "| k | Look (numpy, per direction) | segment walk (test oracle) | lattice scan of the box | "
        "speed-up vs walk | speed-up vs scan |",
        "|---:|---:|---:|---:|---:|---:|",
    ]
    for k in (100, 1_000, 10_000):
        pts = random_points(k, density=density)
        assert visible_from(np.array(pts), 0).tolist() == visible_by_lattice_scan(pts, 0)
        arr = np.array(pts, dtype=np.int64)
        fast = per_call(lambda i, arr=arr, k=k: visible_from(arr, i % k))
        walk = per_call(lambda i, pts=pts, k=k: visible_from_naive(pts, i % k), budget_s=3.0, max_calls=50)
        scan = per_call(
            lambda i, pts=pts, k=k: visible_by_lattice_scan(pts, i % k), budget_s=3.0, max_calls=5
        )
        rows.append(
            f"| {k:,} | {fast * 1e6:,.0f} µs | {walk * 1e6:,.0f} µs | {scan * 1e3:,.1f} ms | "
            f"{walk / fast:,.0f}× | {scan / fast:,.0f}× |"
        )
    return rows


def bench_engine() -> list[str]:
    pts = random_points(100, seed=2)
    pattern = pts  # the run's outcome does not matter here, only its speed
    rows = ["| run | events | events/s |", "|---|---:|---:|"]
    for sched in ("async", "stale-first", "fsync"):
        e = Engine(pts, pattern, CompactLeft(), max_events=200_000)
        start = time.perf_counter()
        advance(e, make_scheduler(sched), 1)
        dt = time.perf_counter() - start
        rows.append(
            f"| 100 robots, compact-left, {sched} ({e.outcome}) | {e.state.events:,} | "
            f"{e.state.events / dt:,.0f} |"
        )
    return rows


if __name__ == "__main__":
    for density in (0.25, 0.01):
        print("\n".join(bench_look(density)))
        print()
    print("\n".join(bench_engine()))
