"""How the searched adversary (apf-viz adversary) does against the built-in schedulers on generated
starts (``sweeps.cells.generated_start``: random robots and pattern in a box, random flips): for each
k and seed, the built-ins' most over seeds 0–19 and what the search found at a budget. Prints a line a
start, with progress; Ctrl+C prints the tally so far.

    python scripts/adversary_campaign.py --ks 5,10,20 --seeds 1-5 --budget 4 --exact
"""

from __future__ import annotations

import argparse
import time

from apf_viz.algorithms import get_algorithm
from apf_viz.explore.adversary import Problem, search
from apf_viz.explore.worst import worst
from apf_viz.sweeps.cells import generated_start, parse_range


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--ks", default="5,10,15")
    ap.add_argument("--seeds", default="1-5")
    ap.add_argument("--budget", type=int, default=200)
    ap.add_argument("--maximize", choices=("moves", "events"), default="moves")
    ap.add_argument("--width", type=int, default=512, help="the widest beam (0: no beam)")
    ap.add_argument("--exact", action="store_true", help="also the exact worst (check --worst), for each")
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
                found = search(problem, args.budget, seed=0, width=args.width)
                total += 1
                beaten += found.beats
                mark = " BEATS" if found.beats else ""
                exact = ""
                if args.exact:
                    w = worst(get_algorithm(problem.algorithm), robots, pattern, [y_up], args.maximize)
                    exact = f", exact {w.value if w.value is not None else w.verdict} ({w.seconds:.1f} s)"
                    assert w.value is None or (found.best.value or 0) <= w.value, "more than the exact worst"
                print(
                    f"k={k} seed {s}: built-ins {found.bar.value}, search {found.best.value} "
                    f"({found.evaluations} schedules searched, {found.seconds:.1f} s){exact}{mark}",
                    flush=True,
                )
    except KeyboardInterrupt:
        print("interrupted")
    print(f"{beaten} of {total} starts beaten in {args.maximize}, {time.perf_counter() - t0:.0f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
