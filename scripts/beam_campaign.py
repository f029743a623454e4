"""The beam over the adversary's choices (explore/beam.py) against the exact worst (``check --worst``)
on generated starts of the adversarial families (core/adversarial_starts.py: a robot far above the
others, on its target's column, on their rows, every robot far apart, symmetric about an axis through
robots), k = 2–6: a beam never cut must equal the exact worst, a narrow one must never exceed it, and
each beam's path must form in the real engine at exactly its cost. Prints progress with an ETA; Ctrl+C
prints the tally so far; exit 1 on the first disagreement (printed).

    python scripts/beam_campaign.py --starts 1000 --far 12
"""

from __future__ import annotations

import argparse
import sys
import time

from apf_viz.core.adversarial_starts import FAMILIES, generate
from apf_viz.explore.beam_campaign import against_exact
from apf_viz.explore.worst import Measure


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--starts", type=int, default=1000)
    ap.add_argument("--far", type=int, default=12, help="how far apart the far robots are, at most")
    ap.add_argument("--first-seed", type=int, default=0)
    args = ap.parse_args()
    families = list(FAMILIES)
    tally = {"agree": 0, "none": 0}
    t0 = time.perf_counter()
    try:
        for n in range(args.starts):
            seed = args.first_seed + n
            case = generate(families[n % len(families)], seed, far=args.far)
            measure: Measure = "moves" if (n // len(families)) % 2 == 0 else "events"
            verdict = against_exact(case.robots, case.pattern, case.y_up, measure, seed)
            if verdict not in ("", "none"):
                print(f"{case.family} seed {seed} ({measure}): {verdict}", flush=True)
                return 1
            tally["none" if verdict else "agree"] += 1
            spent = time.perf_counter() - t0
            eta = spent / (n + 1) * (args.starts - n - 1)
            print(
                f"\r{n + 1}/{args.starts} starts, {spent:.0f} s, ETA {eta:.0f} s  ", end="", file=sys.stderr
            )
    except KeyboardInterrupt:
        print("\ninterrupted: the tally so far", file=sys.stderr)
    print(
        f"\n{tally['agree']} starts: the whole beam is the exact worst, a narrow one never more, every path "
        f"replays to its cost; {tally['none']} without a maximum (not compared); "
        f"{time.perf_counter() - t0:.0f} s"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
