"""The paper's O(kD) bound, measured: moves / (k·D), events per move, wall time and peak memory under
ASYNC for growing k, with no-op activations skipped (the default) and, where it finishes in time, with
every activation kept (``--all-activations``).

D = max(m, n, M, N, k) as in the paper (m, n: height and width of the start's enclosing rectangle;
M, N: the pattern's). Starts and patterns: ``random_solvable_start`` / ``random_pattern`` of the
audit (k cells of a √(3k)-sided box). Each run is a child process, so its peak memory is its own; a run
that takes longer than ``--timeout`` is reported as such (and Ctrl+C keeps the rows printed so far).

Run: python benchmarks/bench_algorithm.py [--ks 5,10,20,40,100] [--all-up-to 100] [--timeout 900]
     python benchmarks/bench_algorithm.py --one K SEED SKIP   (one run in this process, as JSON)

It needs the package installed (``pip install -e .``); a run that fails makes the exit status 1.
"""

from __future__ import annotations

import argparse
import json
import random
import resource
import subprocess
import sys
import time


def one(k: int, seed: int, scheduler: str, skip: bool) -> dict:
    from apf_viz.algorithms import get_algorithm
    from apf_viz.algorithms.apf_opaque_grid.audit import audit_run, random_pattern, random_solvable_start
    from apf_viz.core.budget import paper_D, run_budget
    from apf_viz.core.engine import Engine

    rng = random.Random(k * 1000 + seed)
    start = random_solvable_start(k, rng)
    pattern = random_pattern(k, rng)
    y_up = [rng.random() < 0.5 for _ in range(k)]
    budget = run_budget(start, pattern, skip)
    engine = Engine(
        start,
        pattern,
        get_algorithm("apf-opaque-grid"),
        y_up=y_up,
        max_events=budget.max_events,
        max_moves=budget.max_moves,
        skip_noops=skip,
    )
    t0 = time.perf_counter()
    audit = audit_run(engine, scheduler, seed)
    wall = time.perf_counter() - t0
    d = paper_D(start, pattern)
    return {
        "k": k,
        "D": d,
        "ok": audit.ok,
        "outcome": engine.outcome,
        "moves": audit.moves,
        "events": audit.events,
        "wall": wall,
        "kD": k * d,
        "peak_mib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
    }


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], allow_abbrev=False)
    ap.add_argument("--ks", default="5,10,20,40,100", help="robot counts, one row (or two) each")
    ap.add_argument("--seed", type=int, default=0, help="seed of the start, pattern, flips and scheduler")
    ap.add_argument("--scheduler", default="async", help="the adversary (apf-viz run --help lists them)")
    ap.add_argument("--all-up-to", type=int, default=100, help="also run --all-activations up to this k")
    ap.add_argument("--timeout", type=float, default=900.0, help="seconds per run")
    ap.add_argument(
        "--one",
        nargs=3,
        metavar=("K", "SEED", "SKIP"),
        help="one run of k robots from this seed, SKIP 1 (skip no-ops) or 0 (all activations), in this "
        "process, printed as one JSON object (how the table's rows are made, and the k = 1,000 row)",
    )
    args = ap.parse_args()
    try:
        import apf_viz  # noqa: F401
    except ImportError:
        print("bench_algorithm: apf_viz is not installed: pip install -e . first", file=sys.stderr)
        return 2
    if args.one:
        k, seed, skip = int(args.one[0]), int(args.one[1]), args.one[2] == "1"
        print(json.dumps(one(k, seed, args.scheduler, skip)))
        return 0
    failed = False
    print(
        "| k | D | mode | moves | moves/(k·D) | events | events/move "
        f"| wall time ({args.scheduler}) | peak memory |"
    )
    print("|---:|---:|---|---:|---:|---:|---:|---:|---:|")
    try:
        for k in map(int, args.ks.split(",")):
            for skip in (True, False):
                if not skip and k > args.all_up_to:
                    continue
                mode = "skip no-ops" if skip else "all activations"
                cmd = [sys.executable, __file__, "--scheduler", args.scheduler]
                cmd += ["--one", str(k), str(args.seed)]
                try:
                    out = subprocess.run(
                        [*cmd, "1" if skip else "0"], capture_output=True, text=True, timeout=args.timeout
                    )
                except subprocess.TimeoutExpired:
                    print(f"| {k} | | {mode} | | | | | > {args.timeout:.0f} s | |", flush=True)
                    continue
                r = json.loads(out.stdout) if out.returncode == 0 else {}
                if not r.get("ok"):
                    failed = True
                    why = out.stderr.strip()[-200:] or f"the audit found problems: {r}"
                    print(f"| {k} | | {mode} | failed: {why} |", flush=True)
                    continue
                print(
                    f"| {k:,} | {r['D']:,} | {mode} | {r['moves']:,} | {r['moves'] / r['kD']:.3f} "
                    f"| {r['events']:,} | {r['events'] / max(1, r['moves']):.1f} | {r['wall']:.1f} s "
                    f"| {r['peak_mib']:.0f} MiB |",
                    flush=True,
                )
    except KeyboardInterrupt:
        print("(interrupted: the rows above are complete)", file=sys.stderr)
        return 130
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
