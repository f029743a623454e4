"""The memory campaign: generated starts spread to 10⁹ and 10¹² under every scheduler, each run in a
process of its own under an address-space limit, to its end; every run must end (formed, stuck, limit or
collision) within the limit, and its peak resident memory is reported beside the steps it held.

    python scripts/memory_campaign.py --seeds 3 --out memory.jsonl

Families: those of :mod:`apf_viz.core.adversarial_starts` and ``box`` (k robots anywhere in [−far, far]²).
Each line of ``--out`` is one run (appended as it ends: Ctrl+C keeps what is done). Exit 1 if a run did
not end, or died (a MemoryError, the limit, a crash).
"""

from __future__ import annotations

import argparse
import json
import multiprocessing as mp
import random
import resource
import sys
import time
from pathlib import Path

FARS = (10**9, 10**12)
SCHEDULERS = ("async", "stale-first", "round-robin", "fsync", "ssync")


def start(family: str, seed: int, far: int) -> tuple[list, list, list | None]:
    from apf_viz.core.adversarial_starts import generate
    from apf_viz.core.random_configs import random_pattern

    if family == "box":
        rng = random.Random(f"box:{seed}:{far}")
        k = rng.choice((3, 6, 12))
        robots = sorted({(rng.randint(-far, far), rng.randint(-far, far)) for _ in range(k)})
        return robots, random_pattern(len(robots), 4, 4, seed), None
    case = generate(family, seed, k=random.Random(seed).choice((3, 6, 12)), far=far)
    return case.robots, case.pattern, case.y_up


def one_run(task: tuple, limit_bytes: int, max_recorded: int, queue) -> None:
    """In a child process: the run to its end under the address-space limit; its line on ``queue``."""
    resource.setrlimit(resource.RLIMIT_AS, (limit_bytes, limit_bytes))
    family, far, scheduler, seed = task
    line = {"family": family, "far": far, "scheduler": scheduler, "seed": seed}
    try:
        from apf_viz.algorithms import DEFAULT_ALGORITHM, algorithm_from_command_line
        from apf_viz.core.budget import run_budget
        from apf_viz.core.engine import Engine
        from apf_viz.core.run import advance
        from apf_viz.core.schedulers import make_scheduler

        robots, pattern, y_up = start(family, seed, far)
        algorithm, _ = algorithm_from_command_line(DEFAULT_ALGORITHM)
        budget = run_budget(robots, pattern)
        engine = Engine(
            robots, pattern, algorithm, y_up=y_up, max_events=budget.max_events, max_moves=budget.max_moves,
            max_recorded=max_recorded, fast_forward=True,
        )  # fmt: skip
        t0 = time.monotonic()
        advance(engine, make_scheduler(scheduler), seed)
        line |= {
            "k": len(robots), "outcome": engine.outcome or "running", "events": engine.state.events,
            "entries": engine.history.entries, "seconds": round(time.monotonic() - t0, 1),
        }  # fmt: skip
    except MemoryError:
        line |= {"outcome": "MemoryError"}
    except Exception as e:  # a crash is a finding: reported, not hidden
        line |= {"outcome": f"{type(e).__name__}: {e}"}
    line["peak_rss_mb"] = round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)
    queue.put(line)


def main() -> int:
    from apf_viz.core.adversarial_starts import FAMILIES
    from apf_viz.core.budget import MAX_RECORDED

    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--seeds", type=int, default=2, help="seeds per family, distance and scheduler")
    p.add_argument("--limit-gb", type=float, default=3.0, help="each run's address-space limit")
    p.add_argument("--max-recorded", type=int, default=MAX_RECORDED, help="steps a run may hold")
    p.add_argument("--out", type=Path, required=True, help="JSON Lines, one run a line (appended)")
    args = p.parse_args()
    tasks = [
        (family, far, scheduler, seed)
        for seed in range(1, args.seeds + 1)
        for family in ("box", *FAMILIES)
        for far in FARS
        for scheduler in SCHEDULERS
    ]
    bad, t0 = 0, time.monotonic()
    ctx = mp.get_context("fork")
    try:
        for i, task in enumerate(tasks, 1):
            queue = ctx.Queue()
            child = ctx.Process(
                target=one_run, args=(task, int(args.limit_gb * 2**30), args.max_recorded, queue)
            )
            child.start()
            child.join()
            line = queue.get() if not queue.empty() else {"task": task, "outcome": f"died ({child.exitcode})"}
            bad += line["outcome"] not in ("formed", "stuck", "limit", "collision")
            with args.out.open("a", encoding="utf-8") as f:
                f.write(json.dumps(line) + "\n")
            left = (time.monotonic() - t0) / i * (len(tasks) - i)
            print(
                f"\r{i}/{len(tasks)} runs, {bad} not ended, ETA {left / 60:.0f} min ", end="", file=sys.stderr
            )
    except KeyboardInterrupt:
        print(f"\ninterrupted: the runs done are in {args.out}", file=sys.stderr)
        return 130
    print(file=sys.stderr)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
