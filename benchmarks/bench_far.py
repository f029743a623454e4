"""Far-apart starts with and without fast-forward: which families it speeds up, measured.

    python benchmarks/bench_far.py --fars 10000,100000,1000000 --seeds 1-3

For each family of :mod:`apf_viz.core.adversarial_starts` (k = 3), each distance and seed, the run under
``--scheduler`` with walks, then step by step, each to its end or ``--seconds``: a row per run (the
start's D, as drawn: a family's distance is log-uniform up to ``far``; seconds, steps held, outcome) and
a line per family and distance (the medians, the speed-up).
"""

from __future__ import annotations

import argparse
import statistics
import time

from apf_viz.algorithms import DEFAULT_ALGORITHM, algorithm_from_command_line
from apf_viz.core.adversarial_starts import FAMILIES, generate
from apf_viz.core.budget import paper_D, run_budget
from apf_viz.core.engine import Engine
from apf_viz.core.run import advance
from apf_viz.core.schedulers import make_scheduler


def start_D(family: str, far: int, seed: int) -> int:
    """The paper's D of the start drawn (a family draws its distance log-uniformly up to ``far``)."""
    case = generate(family, seed, k=3, far=far)
    return paper_D(case.robots, case.pattern)


def one(
    family: str, far: int, seed: int, scheduler: str, fast: bool, seconds: float
) -> tuple[float, int, str]:
    case = generate(family, seed, k=3, far=far)
    algorithm, _ = algorithm_from_command_line(DEFAULT_ALGORITHM)
    budget = run_budget(case.robots, case.pattern)
    engine = Engine(
        case.robots, case.pattern, algorithm, y_up=case.y_up, max_events=budget.max_events,
        max_moves=budget.max_moves, fast_forward=fast,
    )  # fmt: skip
    chooser = make_scheduler(scheduler)
    t0 = time.perf_counter()
    while not engine.finished and time.perf_counter() - t0 < seconds:
        advance(engine, chooser, seed, steps=5000)
    return time.perf_counter() - t0, engine.history.entries, engine.outcome or "cut"


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--fars", default="10000,100000,1000000")
    p.add_argument("--seeds", default="1-3")
    p.add_argument("--scheduler", default="stale-first")
    p.add_argument("--seconds", type=float, default=60.0, help="a run is cut after this long")
    p.add_argument("--families", default=",".join(FAMILIES))
    args = p.parse_args()
    lo, _, hi = args.seeds.partition("-")
    seeds = range(int(lo), int(hi or lo) + 1)
    print("| family | far | seed | D | with walks: s, steps, outcome | step by step: s, steps, outcome |")
    print("|---|---:|---:|---:|---|---|")
    summary = []
    for family in args.families.split(","):
        for far in map(int, args.fars.split(",")):
            fast, slow = [], []
            for seed in seeds:
                a = one(family, far, seed, args.scheduler, True, args.seconds)
                b = one(family, far, seed, args.scheduler, False, args.seconds)
                fast.append(a[0])
                slow.append(b[0])
                cells = [f"{r[0]:.2f}, {r[1]:,}, {r[2]}" for r in (a, b)]
                d = start_D(family, far, seed)
                print(f"| {family} | {far:,} | {seed} | {d:,} | {cells[0]} | {cells[1]} |", flush=True)
            f, s = statistics.median(fast), statistics.median(slow)
            summary.append(
                f"{family} at {far:,}: median {f:.2f} s with walks, {s:.2f} s step by step ({s / f:.0f}×)"
            )
    print("\n" + "\n".join(summary))


if __name__ == "__main__":
    main()
