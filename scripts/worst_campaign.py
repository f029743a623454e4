"""How far the built-in schedulers are from the adversary's best play, on generated small starts: for
each start (k = 3–5, a random pattern and flips), the exact worst moves and events (``check --worst``)
against the most any automatic scheduler reaches over seeds 0–19. Prints progress with an ETA; Ctrl+C
prints the tally so far.

    python scripts/worst_campaign.py --starts 100 --seed 11
    python scripts/worst_campaign.py --shipped      # docs/ADVERSARY.md's table: three shipped starts
"""

from __future__ import annotations

import argparse
import random
import sys
import time

from apf_viz.algorithms import get_algorithm
from apf_viz.algorithms.apf_opaque_grid.audit import random_pattern, random_solvable_start
from apf_viz.core.budget import run_budget
from apf_viz.core.engine import Engine
from apf_viz.core.schedulers import AUTOMATIC, make_scheduler, step_rng
from apf_viz.explore.worst import MEASURES, worst


def built_ins_most(algorithm, start, pattern, y_up) -> dict[str, int]:
    """The most moves and events any automatic scheduler reaches, seeds 0–19, in a run that forms."""
    most = {"moves": 0, "events": 0}
    budget = run_budget(start, pattern, True)
    for name in AUTOMATIC:
        scheduler = make_scheduler(name)
        for seed in range(20):
            e = Engine(start, pattern, algorithm, y_up=y_up, max_events=budget.max_events)
            while not e.finished:
                e.apply(scheduler.choose(e, step_rng(seed, e.step_index)))
            if e.outcome == "formed":
                most["moves"] = max(most["moves"], e.state.moves)
                most["events"] = max(most["events"], e.state.events)
    return most


SHIPPED = (("one-on-L1-3", "corner-3"), ("vertical-line-4", "tee-4"), ("robots-on-K-5", "hook-5"))


def shipped_table(algorithm) -> None:
    """docs/ADVERSARY.md's table: for each shipped start (the robots file's flips, seed 0), the exact
    worst moves and events, the built-ins' most, the states searched and the time of both searches."""
    from apf_viz.core.budget import paper_D
    from apf_viz.core.formats import load_pattern, load_robots
    from apf_viz.core.grid import as_point
    from apf_viz.demos import shipped_file

    def shipped(name: str, kind: str):
        path = shipped_file(name, kind)
        if path is None:
            raise SystemExit(f"no shipped {kind} file {name!r}")
        return path

    for robots_name, pattern_name in SHIPPED:
        robots = load_robots(shipped(robots_name, "robots"))
        start = [as_point(p) for p in robots.robots]
        pattern = [as_point(p) for p in load_pattern(shipped(pattern_name, "pattern")).points]
        y_up = tuple(robots.flips(0))
        kd = len(start) * paper_D(start, pattern)
        most = built_ins_most(algorithm, start, pattern, y_up)
        cells = []
        t0 = time.perf_counter()
        for measure in MEASURES:
            found = worst(algorithm, start, pattern, [y_up], measure)
            value = found.value if found.value is not None else 0
            cells.append(f"{value} ({value / kd:.2f}) | {most[measure]}")
        print(
            f"| {robots_name} + {pattern_name} | {len(start)} | {kd} | {' | '.join(cells)} | "
            f"{found.states:,} | {time.perf_counter() - t0:.1f} s |"
        )


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--starts", type=int, default=100)
    parser.add_argument("--seed", type=int, default=11)
    parser.add_argument("--max-states", type=int, default=300_000)
    parser.add_argument("--shipped", action="store_true", help="the table for three shipped starts")
    args = parser.parse_args()
    algorithm = get_algorithm("apf-opaque-grid")
    if args.shipped:
        shipped_table(algorithm)
        return 0
    rng = random.Random(args.seed)
    compared = {m: 0 for m in MEASURES}
    beaten = {m: 0 for m in MEASURES}
    unanswered = 0
    t0 = time.perf_counter()
    try:
        for n in range(1, args.starts + 1):
            k = rng.choice([3, 4, 5])
            start, pattern = random_solvable_start(k, rng), random_pattern(k, rng)
            y_up = [rng.random() < 0.5 for _ in range(k)]
            most = built_ins_most(algorithm, start, pattern, y_up)
            for measure in MEASURES:
                found = worst(algorithm, start, pattern, [y_up], measure, max_states=args.max_states)
                if found.value is None:
                    unanswered += 1
                    continue
                compared[measure] += 1
                beaten[measure] += found.value > most[measure]
                assert found.value >= most[measure], (start, pattern, y_up, measure)  # a maximum
            spent = time.perf_counter() - t0
            eta = spent / n * (args.starts - n)
            print(f"{n}/{args.starts} starts, {spent:.0f} s, ETA {eta:.0f} s", file=sys.stderr, flush=True)
    except KeyboardInterrupt:
        print("interrupted: the tally so far", file=sys.stderr)
    for measure in MEASURES:
        print(
            f"{measure}: the exact worst exceeds every built-in scheduler (seeds 0-19) on "
            f"{beaten[measure]} of {compared[measure]} starts"
        )
    print(f"no maximum (a failure, a cycle, or the state budget): {unanswered} measure(s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
