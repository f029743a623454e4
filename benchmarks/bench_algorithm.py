"""The paper's O(kD) bound, measured: moves / (k·D), events per move, wall time, time per move and peak
memory under ASYNC, against k (D ≈ k) and against D (k fixed, robots spread over a growing box).

Modes: ``walks`` (the default of ``apf-viz run``: no-op activations skipped, a lone robot's repeating
cycles fast-forwarded: as one walk where its sight stays the same, else as a run of forced cycles, each
Looked and decided anew), ``steps`` (skipped, every event applied one by one: ``--no-fast-forward``) and
``all`` (every activation kept: ``--all-activations``). The modes of one row are the same run, event for
event; the table shows what each costs.

D = max(m, n, M, N, k) as in the paper (m, n: height and width of the start's enclosing rectangle;
M, N: the pattern's). k rows: ``random_solvable_start`` / ``random_pattern`` of the audit (k cells of a
√(3k)-sided box). D rows: ``apf-viz random-robots --count K --width B --height B --seed SEED`` and the
audit's random pattern of k cells. Each run is a child process, so its peak memory is its own; a run
that takes longer than ``--timeout`` is reported as such (and Ctrl+C keeps the rows printed so far).

Run: python benchmarks/bench_algorithm.py [--ks 5,10,20,40,100] [--boxes 10,1000,10000] [--box-k 10]
         [--steps-up-to 100000] [--all-up-to 100] [--timeout 900]
     python benchmarks/bench_algorithm.py --one K SEED MODE [BOX]   (one run in this process, as JSON)

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


def one(k: int, seed: int, scheduler: str, mode: str, box: int | None = None) -> dict:
    from apf_viz.algorithms import get_algorithm
    from apf_viz.algorithms.apf_opaque_grid.audit import audit_run, random_pattern, random_solvable_start
    from apf_viz.core.budget import paper_D, run_budget
    from apf_viz.core.engine import Engine
    from apf_viz.core.random_configs import random_robots

    rng = random.Random(k * 1000 + seed)
    start = random_solvable_start(k, rng) if box is None else random_robots(k, box, box, seed)
    pattern = random_pattern(k, rng)
    y_up = [rng.random() < 0.5 for _ in range(k)]
    skip = mode != "all"
    budget = run_budget(start, pattern, skip)
    engine = Engine(
        start,
        pattern,
        get_algorithm("apf-opaque-grid"),
        y_up=y_up,
        max_events=budget.max_events,
        max_moves=budget.max_moves,
        skip_noops=skip,
        fast_forward=mode == "walks",
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
        "walks": engine.walks,
        "forced": engine.forced_walks,
        "wall": wall,
        "kD": k * d,
        "peak_mib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
    }


MODES = {"walks": "walks", "steps": "step by step", "all": "all activations"}


def _row(args: argparse.Namespace, k: int, mode: str, box: int | None) -> bool:
    """Run one row in a child process and print it; False if it failed."""
    cmd = [sys.executable, __file__, "--scheduler", args.scheduler, "--one", str(k), str(args.seed), mode]
    if box is not None:
        cmd.append(str(box))
    try:
        out = subprocess.run(cmd, capture_output=True, text=True, timeout=args.timeout)
    except subprocess.TimeoutExpired:
        print(f"| {k:,} | | {MODES[mode]} | | | | | | > {args.timeout:.0f} s | | |", flush=True)
        return True
    r = json.loads(out.stdout) if out.returncode == 0 else {}
    if not r.get("ok"):
        why = out.stderr.strip()[-200:] or f"the audit found problems: {r}"
        print(f"| {k:,} | | {MODES[mode]} | failed: {why} |", flush=True)
        return False
    per_move = r["wall"] / max(1, r["moves"]) * 1e6
    print(
        f"| {k:,} | {r['D']:,} | {MODES[mode]} | {r['moves']:,} | {r['moves'] / r['kD']:.3f} "
        f"| {r['events']:,} | {r['events'] / max(1, r['moves']):.1f} | {r['walks']:,} + {r['forced']:,} "
        f"| {r['wall']:.2f} s "
        f"| {per_move:.2f} µs | {r['peak_mib']:.0f} MiB |",
        flush=True,
    )
    return True


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], allow_abbrev=False)
    ap.add_argument("--ks", default="5,10,20,40,100", help="robot counts of the k rows (D ≈ k); '' for none")
    ap.add_argument("--boxes", default="", help="box sides of the D rows (k = --box-k), e.g. 10,1000,10000")
    ap.add_argument("--box-k", type=int, default=10, help="robots in the D rows")
    ap.add_argument("--seed", type=int, default=0, help="seed of the start, pattern, flips and scheduler")
    ap.add_argument("--scheduler", default="async", help="the adversary (apf-viz run --help lists them)")
    ap.add_argument(
        "--steps-up-to",
        type=int,
        default=100_000,
        help="also run step by step while k·max(k, box) is at most this",
    )
    ap.add_argument("--all-up-to", type=int, default=100, help="also run --all-activations up to this k")
    ap.add_argument("--timeout", type=float, default=900.0, help="seconds per run")
    ap.add_argument(
        "--one",
        nargs="+",
        metavar="K SEED MODE [BOX]",
        help="one run of k robots from this seed, MODE walks, steps or all, BOX the side of a spread start, "
        "in this process, printed as one JSON object (how the table's rows are made)",
    )
    args = ap.parse_args()
    try:
        import apf_viz  # noqa: F401
    except ImportError:
        print("bench_algorithm: apf_viz is not installed: pip install -e . first", file=sys.stderr)
        return 2
    if args.one:
        k, seed, mode = int(args.one[0]), int(args.one[1]), args.one[2]
        box = int(args.one[3]) if len(args.one) > 3 else None
        print(json.dumps(one(k, seed, args.scheduler, mode, box)))
        return 0
    print(
        "| k | D | mode | moves | moves/(k·D) | events | events/move | walks + forced runs "
        f"| wall time ({args.scheduler}) | per move | peak memory |"
    )
    print("|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    rows: list[tuple[int, int | None]] = [(k, None) for k in map(int, filter(None, args.ks.split(",")))]
    rows += [(args.box_k, b) for b in map(int, filter(None, args.boxes.split(",")))]
    ok = True
    try:
        for k, box in rows:
            size = k * max(k, box or 0)
            for mode in ("walks", "steps", "all"):
                if mode == "steps" and size > args.steps_up_to:
                    continue
                if mode == "all" and (box is not None or k > args.all_up_to):
                    continue
                ok = _row(args, k, mode, box) and ok
    except KeyboardInterrupt:
        print("(interrupted: the rows above are complete)", file=sys.stderr)
        return 130
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
