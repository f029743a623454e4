"""Search for one counterexample per resolution: a start and a schedule on which the algorithm with every
resolution *except* that one fails, while the same schedule with all of them does not.

Writes tests/gap_traces/<RES>.jsonl (the failing run, replayable with `apf-viz replay`) and prints a summary.
Run from the repository root: python scripts/find_gap_traces.py [--budget-s 120] [--only G1,E2]
"""

from __future__ import annotations

import argparse
import random
import time
from pathlib import Path

from apf_viz.algorithms import get_algorithm
from apf_viz.algorithms.apf_opaque_grid.audit import audit_run, random_pattern, random_solvable_start
from apf_viz.algorithms.apf_opaque_grid.resolutions import ALL, RESOLUTIONS
from apf_viz.core.engine import Engine
from apf_viz.core.files import write_atomic
from apf_viz.core.formats import trace_text
from apf_viz.core.run import trace_header

OUT = Path("tests/gap_traces")


def ablated(name: str) -> str:
    return "apf-opaque-grid@" + ",".join(r for r in RESOLUTIONS if r != name)


def same_schedule_with_all(engine: Engine) -> bool:
    """Replay the failing run's robot choices with every resolution on: True if nothing goes wrong."""
    fixed = Engine(
        engine.start,
        engine.pattern,
        get_algorithm("apf-opaque-grid"),
        y_up=engine.y_up,
        light_semantics=engine.light_semantics,
        max_events=200_000,
    )
    for step in engine.history.steps:
        if fixed.finished:
            break
        fixed.step(step.record.robots, round=step.record.round)
        if fixed.outcome == "collision" or fixed.state.lights.count("leader") > 1:
            return False
    if not fixed.finished:
        audit = audit_run(fixed, "async", 1)
        return audit.ok
    return fixed.outcome == "formed"


def search(name: str, budget_s: float, rng: random.Random) -> tuple[Engine, str, int, list[str]] | None:
    t0 = time.perf_counter()
    algorithm = ablated(name)
    while time.perf_counter() - t0 < budget_s:
        k = rng.randint(1, 8)
        start = random_solvable_start(k, rng, box=rng.choice([3, 4, 5, 6]))
        pattern = random_pattern(k, rng, box=4)
        y_up = [rng.random() < 0.5 for _ in range(k)]
        for scheduler in ("async", "stale-first", "ssync"):
            for semantics in ("compute", "lc-atomic"):
                seed = rng.randrange(1 << 20)
                engine = Engine(
                    start,
                    pattern,
                    get_algorithm(algorithm),
                    y_up=y_up,
                    max_events=30_000,
                    light_semantics=semantics,
                )
                audit = audit_run(engine, scheduler, seed)
                if not audit.ok and same_schedule_with_all(engine):
                    return engine, scheduler, seed, audit.problems
    return None


LIVELOCK_EVENTS = 3000  # a livelock is saved as its first events: enough to see it repeat


def truncated(engine: Engine, max_events: int) -> Engine:
    """The same schedule, stopped at ``max_events`` (the run then ends with outcome limit)."""
    short = Engine(
        engine.start,
        engine.pattern,
        engine.algorithm,
        y_up=engine.y_up,
        light_semantics=engine.light_semantics,
        max_events=max_events,
    )
    for step in engine.history.steps:
        if short.finished:
            break
        short.step(step.record.robots, round=step.record.round)
    return short


def literal_failures(budget_s: float, rng: random.Random) -> None:
    """One trace of the literal variant per kind of failure (collision, deadlock, livelock, two leaders)."""
    out = Path("tests/literal_traces")
    out.mkdir(parents=True, exist_ok=True)
    kinds: dict[str, Engine] = {}
    t0 = time.perf_counter()
    while time.perf_counter() - t0 < budget_s and len(kinds) < 4:
        k = rng.randint(2, 8)
        start = random_solvable_start(k, rng, box=rng.choice([3, 4, 5]))
        pattern = random_pattern(k, rng, box=4)
        y_up = [rng.random() < 0.5 for _ in range(k)]
        scheduler, seed = rng.choice(["async", "stale-first"]), rng.randrange(1 << 20)
        engine = Engine(
            start, pattern, get_algorithm("apf-opaque-grid-literal"), y_up=y_up, max_events=30_000
        )
        audit = audit_run(engine, scheduler, seed)
        kind = (
            "two-leaders"
            if audit.max_leaders > 1
            else {"collision": "collision", "stuck": "deadlock", "limit": "livelock"}.get(audit.outcome)
        )
        if kind and kind not in kinds:
            if engine.outcome == "limit":
                engine = truncated(engine, LIVELOCK_EVENTS)
            kinds[kind] = engine
            header = trace_header(
                engine, scheduler, seed, {"literal_failure": kind, "problems": audit.problems}
            )
            write_atomic(out / f"{kind}.jsonl", trace_text(header, engine.history.events()))
            print(f"literal {kind}: k={k} start={start} {scheduler} seed={seed}: {'; '.join(audit.problems)}")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--literal", action="store_true", help="save literal-variant failures instead")
    ap.add_argument("--budget-s", type=float, default=120)
    ap.add_argument("--only", default=",".join(sorted(ALL)))
    ap.add_argument("--seed", type=int, default=7)
    args = ap.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    rng = random.Random(args.seed)
    if args.literal:
        literal_failures(args.budget_s * 4, rng)
        return
    for name in args.only.split(","):
        found = search(name, args.budget_s, rng)
        if found is None:
            print(f"{name}: no counterexample in {args.budget_s:.0f}s of random search")
            continue
        engine, scheduler, seed, problems = found
        if engine.outcome == "limit":
            engine = truncated(engine, LIVELOCK_EVENTS)
        header = trace_header(engine, scheduler, seed, {"shows_gap": name, "problems": problems})
        write_atomic(OUT / f"{name}.jsonl", trace_text(header, engine.history.events()))
        print(
            f"{name}: k={engine.k} start={list(engine.start)} {scheduler} seed={seed} "
            f"{engine.light_semantics}: {'; '.join(problems)} ({engine.state.events} events)"
        )


if __name__ == "__main__":
    main()
