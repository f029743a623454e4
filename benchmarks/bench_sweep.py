"""Sweep throughput: runs per second on a Dask LocalCluster of this machine's cores against the same runs
serially in one process, and the cluster's overhead per run.

Run: python benchmarks/bench_sweep.py [--ks 8,12,16] [--seeds 1-8]
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

from apf_viz.sweep import _cores, grid, parse_range, run_cell, run_sweep


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--ks", default="8,12,16")
    ap.add_argument("--seeds", default="1-8")
    args = ap.parse_args()
    ks, seeds = parse_range(args.ks, "--ks"), parse_range(args.seeds, "--seeds")
    cells = grid(ks, seeds, ["async"], ["apf-opaque-grid"], ["compute"])
    t0 = time.perf_counter()
    for c in cells:
        run_cell(c)
    serial = time.perf_counter() - t0
    with tempfile.TemporaryDirectory() as d:
        t0 = time.perf_counter()
        rows = run_sweep(cells, Path(d) / "r.parquet")
        parallel = time.perf_counter() - t0
    workers = _cores()
    print(f"| runs | serial, one process | LocalCluster, {workers} workers | speed-up | overhead per run |")
    print("|---:|---:|---:|---:|---:|")
    overhead = (parallel * workers - sum(r["wall_s"] for r in rows)) / len(rows)
    print(
        f"| {len(cells)} | {serial:.1f} s ({len(cells) / serial:.1f} runs/s) | {parallel:.1f} s "
        f"({len(cells) / parallel:.1f} runs/s, cluster start included) | {serial / parallel:.2f}× "
        f"| {overhead * 1000:.0f} ms |"
    )


if __name__ == "__main__":
    main()
