"""Soak: thousands of random solvable starts through the paper's algorithm under every scheduler, as an
``apf-viz sweep`` (Dask, every core, resumable: the same --out continues where it stopped).

Run: python benchmarks/soak.py [--starts 2000] [--max-k 14] [--algorithm apf-opaque-grid] [--lc-atomic]
     [--out soak.parquet]
Prints the summary and every run that did not form (with its trace under soak-traces/); exit 1 if any.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from apf_viz.sweeps import grid, report_progress, run_sweep, summary

SCHEDULERS = ("async", "stale-first", "ssync", "fsync", "round-robin")


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--starts", type=int, default=2000, help="starts in all, spread over k = 3 .. --max-k")
    ap.add_argument("--max-k", type=int, default=14)
    ap.add_argument("--algorithm", default="apf-opaque-grid")
    ap.add_argument("--lc-atomic", action="store_true")
    ap.add_argument("--schedulers", default=",".join(SCHEDULERS))
    ap.add_argument("--out", type=Path, default=Path("soak.parquet"))
    args = ap.parse_args()
    ks = list(range(3, args.max_k + 1))
    seeds = list(range(1, max(1, args.starts // len(ks)) + 1))
    semantics = ["lc-atomic" if args.lc_atomic else "compute"]
    cells = grid(ks, seeds, args.schedulers.split(","), [args.algorithm], semantics)
    try:
        rows = run_sweep(cells, args.out, traces=Path("soak-traces"), progress=report_progress)
    except KeyboardInterrupt:
        return 130
    print(summary(rows))
    failed = [r for r in rows if r["outcome"] != "formed"]
    for r in failed:
        print(f"FAIL k={r['k']} seed={r['seed']} {r['scheduler']}: {r['outcome']} {r['error']} {r['trace']}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
