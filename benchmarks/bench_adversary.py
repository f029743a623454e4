"""The searched adversary's throughput (apf-viz adversary, explore/adversary.py): schedules tried a
second, each a whole run of the engine to FORMED, on generated starts (``sweeps.cells.generated_start``)
of k = 10 and k = 30, one core; and what the search found there against the built-ins at that budget.
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
    print("| k | schedules tried | seconds | schedules/s | built-ins' most moves | found |")
    print("|---:|---:|---:|---:|---:|---:|")
    for k in (int(x) for x in args.ks.split(",")):
        robots, pattern, y_up = generated_start(k, args.seed)
        problem = Problem(
            "apf-opaque-grid", tuple(map(tuple, robots)), tuple(map(tuple, pattern)), tuple(y_up), "moves"
        )
        found = search(problem, args.budget, seed=0)
        rate = found.evaluations / found.seconds
        print(
            f"| {k} | {found.evaluations} | {found.seconds:.1f} | {rate:.1f} | {found.bar.value} | "
            f"{found.best.value} |",
            flush=True,
        )


if __name__ == "__main__":
    main()
