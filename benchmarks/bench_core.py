"""Core benchmarks: Look time against the naive lattice walk, the patched views' cost per move, and
engine events per second.

Run: python benchmarks/bench_core.py   (prints a Markdown table; not part of the test suite)
"""

from __future__ import annotations

import random
import sys
import time
from math import gcd
from pathlib import Path

import numpy as np

from apf_viz.algorithms.examples import CompactLeft
from apf_viz.core.engine import Engine
from apf_viz.core.grid import visible_from
from apf_viz.core.run import advance
from apf_viz.core.schedulers import make_scheduler
from apf_viz.core.visibility import Views

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))  # the tests' oracle, from a checkout
from tests.oracle import visible_by_lattice_walk


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
        walk = per_call(
            lambda i, pts=pts, k=k: visible_by_lattice_walk(pts, i % k), budget_s=3.0, max_calls=50
        )
        scan = per_call(
            lambda i, pts=pts, k=k: visible_by_lattice_scan(pts, i % k), budget_s=3.0, max_calls=5
        )
        rows.append(
            f"| {k:,} | {fast * 1e6:,.0f} µs | {walk * 1e6:,.0f} µs | {scan * 1e3:,.1f} ms | "
            f"{walk / fast:,.0f}× | {scan / fast:,.0f}× |"
        )
    return rows


def _patch_cost(k: int) -> tuple[float, float]:
    """Seconds per move to keep all k views current, and to compute them all from scratch instead."""
    pts = random_points(k, seed=3)
    arr = np.array(pts, dtype=np.int64)
    views = Views(arr, ["off"] * k, [True] * k)
    for r in range(k):
        views.view(r)
    occupied = set(pts)
    rng = random.Random(4)
    steps = [(1, 0), (-1, 0), (0, 1), (0, -1)]

    def one_move(_i: int) -> None:
        while True:
            m = rng.randrange(k)
            x, y = int(arr[m, 0]), int(arr[m, 1])
            dx, dy = rng.choice(steps)
            if (x + dx, y + dy) not in occupied:
                break
        occupied.discard((x, y))
        occupied.add((x + dx, y + dy))
        arr[m] = (x + dx, y + dy)
        views.moved([m], [(x, y)])

    patched = per_call(one_move, budget_s=2.0, max_calls=500)
    scratch = per_call(lambda i: [visible_from(arr, r) for r in range(k)], budget_s=2.0, max_calls=20)
    return patched, scratch


def bench_patched_views() -> list[str]:
    """What a move costs the patched views (every robot's view kept current), against computing every
    robot's view from scratch after it, as a Look per robot would without them."""
    rows = [
        "| k | patch all k views after one move | all k views from scratch | per view, patched |",
        "|---:|---:|---:|---:|",
    ]
    for k in (100, 1_000):
        patched, scratch = _patch_cost(k)
        rows.append(
            f"| {k:,} | {patched * 1e3:,.2f} ms | {scratch * 1e3:,.1f} ms | {patched / k * 1e6:,.1f} µs |"
        )
    return rows


def bench_engine() -> list[str]:
    pts = random_points(100, seed=2)
    # The run's outcome does not matter here, only its speed; but not the start itself: a start that
    # is the pattern is formed at time 0, and the table once measured no event at all.
    pattern = random_points(100, seed=3)
    rows = ["| run | events | moves | wall time | events/s |", "|---|---:|---:|---:|---:|"]
    for sched in ("async", "stale-first", "fsync"):
        e = Engine(pts, pattern, CompactLeft(), max_events=200_000)
        start = time.perf_counter()
        advance(e, make_scheduler(sched), 1)
        dt = time.perf_counter() - start
        assert e.state.events > 0, "the benchmark run did nothing"
        rows.append(
            f"| 100 robots, compact-left, {sched} ({e.outcome}) | {e.state.events:,} | {e.state.moves:,} | "
            f"{dt:.2f} s | {e.state.events / dt:,.0f} |"
        )
    return rows


if __name__ == "__main__":
    for density in (0.25, 0.01):
        print("\n".join(bench_look(density)))
        print()
    print("\n".join(bench_patched_views()))
    print()
    print("\n".join(bench_engine()))
