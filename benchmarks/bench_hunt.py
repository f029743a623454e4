"""The hunt's throughput (apf-viz hunt, explore/hunt.py): starts searched exhaustively an hour on one
core, by k, on the hunt's own generated starts (every family in turn), with the explorer as it is and,
``--plain``, with the per-robot views and the cyclic collector as before 2026-12-07 (the comparison
docs/PERFORMANCE.md, "The hunt", records).
Run: python benchmarks/bench_hunt.py [--ks 8,14,20,28] [--starts 8] [--plain]"""

from __future__ import annotations

import argparse
import contextlib
import time

from apf_viz.explore import explorer, state_space
from apf_viz.explore.hunt import hunt_one, hunt_starts


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--ks", default="8,14,20,28")
    ap.add_argument("--starts", type=int, default=8, help="starts per k (the families in turn)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--plain", action="store_true", help="per-robot views, cyclic GC on (the old path)")
    args = ap.parse_args()
    if args.plain:
        state_space.SIGHT_LINES_FROM = 10**9
        explorer._no_cyclic_gc = contextlib.nullcontext  # type: ignore[assignment]
    print("| k | starts | states (mean) | seconds (mean) | states/s | starts/hour, one core |")
    print("|---:|---:|---:|---:|---:|---:|")
    for k in (int(x) for x in args.ks.split(",")):
        rows = []
        for start in hunt_starts([k], args.starts, args.seed):
            t = time.perf_counter()
            row = hunt_one(start, "apf-opaque-grid", 500_000)
            rows.append((row["states"], time.perf_counter() - t))
        states = sum(r[0] for r in rows) / len(rows)
        seconds = sum(r[1] for r in rows) / len(rows)
        print(
            f"| {k} | {len(rows)} | {states:,.0f} | {seconds:.2f} | {states / seconds:,.0f} | "
            f"{3600 / seconds:,.0f} |"
        )


if __name__ == "__main__":
    main()
