"""Sweep throughput: runs per second on a Dask LocalCluster of this machine's cores against the same runs
serially in one process, and the cluster's overhead per run.

Run: python benchmarks/bench_sweep.py [--ks 8,12,16] [--seeds 1-8]
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

from apf_viz.sweeps import grid, parse_range, run_cell, run_sweep, usable_cores


def main() -> None:
    from dask.distributed import Client, LocalCluster

    ap = argparse.ArgumentParser()
    ap.add_argument("--ks", default="20,30,40")
    ap.add_argument("--seeds", default="1-6")
    args = ap.parse_args()
    ks, seeds = parse_range(args.ks, "--ks"), parse_range(args.seeds, "--seeds")
    cells = grid(ks, seeds, ["async"], ["apf-opaque-grid"], ["compute"])
    t0 = time.perf_counter()
    for c in cells:
        run_cell(c)
    serial = time.perf_counter() - t0
    workers = usable_cores()
    t0 = time.perf_counter()
    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None)
    client = Client(cluster)
    start = time.perf_counter() - t0
    t0 = time.perf_counter()
    rows = client.gather(client.map(run_cell, cells, pure=False))
    parallel = time.perf_counter() - t0
    client.close()
    cluster.close()
    with tempfile.TemporaryDirectory() as d:  # the whole command's path: results written as they come
        t0 = time.perf_counter()
        run_sweep(cells, Path(d) / "r.parquet")
        whole = time.perf_counter() - t0
    overhead = (parallel * workers - sum(r["wall_s"] for r in rows)) / len(rows)
    head = f"| runs | serial, one process | {workers} Dask workers | speed-up | overhead per run"
    print(f"{head} | cluster start | run_sweep, all included |")
    print("|---:|---:|---:|---:|---:|---:|---:|")
    print(
        f"| {len(cells)} | {serial:.1f} s ({len(cells) / serial:.2f} runs/s) | {parallel:.1f} s "
        f"({len(cells) / parallel:.2f} runs/s) | {serial / parallel:.2f}× | {overhead * 1000:.0f} ms "
        f"| {start:.1f} s | {whole:.1f} s |"
    )


if __name__ == "__main__":
    main()
