"""Explore every start with k ≤ 3 robots in a 4×4 box (up to translation) under ASYNC, all flips, and print
a Markdown table for docs/VERIFICATION.md. Run: python scripts/verify_small_starts.py [--max-k 3]"""

from __future__ import annotations

import argparse
import time

from apf_viz.algorithms import get_algorithm
from apf_viz.core.symmetry import unsolvable_axis
from apf_viz.explore.check import all_flips, check
from apf_viz.explore.small_starts import box_starts


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--max-k", type=int, default=3)
    ap.add_argument("--algorithm", default="apf-opaque-grid")
    ap.add_argument("--light-semantics", default="compute", choices=["compute", "lc-atomic"])
    args = ap.parse_args()
    algorithm = get_algorithm(args.algorithm)
    print("| k | start | solvable | verdict (all flips) | states | time |")
    print("|---:|---|---|---|---:|---:|")
    summary: dict[str, int] = {}
    t_all = time.perf_counter()
    for k in range(1, args.max_k + 1):
        pattern = [(i, 0) for i in range(k)]
        for start in box_starts(k):
            axis = unsolvable_axis(start)
            r, y_up = check(
                algorithm,
                start,
                pattern,
                all_flips(k),
                "async",
                2_000_000,
                progress=False,
                light_semantics=args.light_semantics,
            )
            verdict = r.verdict if r.verdict == "verified" else f"{r.verdict} (flips {list(y_up)})"
            summary[f"k={k} {'solvable' if axis is None else 'unsolvable'} {r.verdict}"] = (
                summary.get(f"k={k} {'solvable' if axis is None else 'unsolvable'} {r.verdict}", 0) + 1
            )
            print(
                f"| {k} | {start} | {'yes' if axis is None else f'no (y = {float(axis):g})'} | {verdict} "
                f"| {r.states:,} | {r.seconds:.2f} s |",
                flush=True,
            )
    print()
    for key, n in sorted(summary.items()):
        print(f"- {key}: {n}")
    print(f"- total time {time.perf_counter() - t_all:.0f} s")


if __name__ == "__main__":
    main()
