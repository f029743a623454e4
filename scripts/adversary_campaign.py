"""How the searched adversary (apf-viz adversary) does against the built-in schedulers on generated
starts (``sweeps.cells.generated_start``: random robots and pattern in a box, random flips): for each
k and seed, the built-ins' most over seeds 0–19 and what the search found at a budget. Prints a line a
start, with progress; Ctrl+C prints the tally so far.

    python scripts/adversary_campaign.py --ks 5,10,15 --seeds 1-5 --budget 300 --maximize moves
"""

from __future__ import annotations

import argparse
import time

from apf_viz.explore.adversary import Problem, search
from apf_viz.sweeps.cells import generated_start, parse_range


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--ks", default="5,10,15")
    ap.add_argument("--seeds", default="1-5")
    ap.add_argument("--budget", type=int, default=300)
    ap.add_argument("--maximize", choices=("moves", "events"), default="moves")
    args = ap.parse_args()
    ks, seeds = parse_range(args.ks, "--ks"), parse_range(args.seeds, "--seeds")
    beaten = total = 0
    t0 = time.perf_counter()
    try:
        for k in ks:
            for s in seeds:
                robots, pattern, y_up = generated_start(k, s)
                problem = Problem(
                    "apf-opaque-grid", tuple(map(tuple, robots)), tuple(map(tuple, pattern)), tuple(y_up),
                    args.maximize,
                )  # fmt: skip
                found = search(problem, args.budget, seed=0)
                total += 1
                beaten += found.beats
                mark = " BEATS" if found.beats else ""
                print(
                    f"k={k} seed {s}: built-ins {found.bar.value}, search {found.best.value} "
                    f"({found.evaluations} schedules, {found.seconds:.1f} s){mark}",
                    flush=True,
                )
    except KeyboardInterrupt:
        print("interrupted")
    print(f"{beaten} of {total} starts beaten in {args.maximize}, {time.perf_counter() - t0:.0f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
