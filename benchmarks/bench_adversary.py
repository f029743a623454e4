"""The searched adversary's throughput (apf-viz adversary, explore/adversary.py) on generated starts
(``sweeps.cells.generated_start``) of k = 10 and k = 30, one core: the beam's time and states a second
over the adversary's choices (explore/beam.py), then schedules tried a second (each a whole run of the
engine to FORMED); and what the search found against the built-ins at that budget.
Run: python benchmarks/bench_adversary.py [--ks 10,30] [--budget 160]"""

from __future__ import annotations

import argparse

from apf_viz.explore.adversary import Problem, search
from apf_viz.sweeps.cells import generated_start


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--ks", default="10,30")
    ap.add_argument("--budget", type=int, default=160)
    ap.add_argument("--seed", type=int, default=1, help="the generated start's")
    args = ap.parse_args()
    print(
        "| k | beam: seconds, states/s | schedules tried | seconds | schedules/s | built-ins' most | found |"
    )
    print("|---:|---:|---:|---:|---:|---:|---:|")
    for k in (int(x) for x in args.ks.split(",")):
        robots, pattern, y_up = generated_start(k, args.seed)
        problem = Problem(
            "apf-opaque-grid", tuple(map(tuple, robots)), tuple(map(tuple, pattern)), tuple(y_up), "moves"
        )
        found = search(problem, args.budget, seed=0)
        b = found.beam
        assert b is not None
        runs = found.evaluations - 1  # the beam is one
        spent = found.seconds - b.seconds
        rate = runs / spent
        print(
            f"| {k} | {b.seconds:.1f}, {b.states / b.seconds:,.0f} | {runs} | {spent:.1f} "
            f"| {rate:.1f} | {found.bar.value} | {found.best.value} |",
            flush=True,
        )


if __name__ == "__main__":
    main()
