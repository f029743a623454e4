"""The fast-forward campaign: thousands of generated adversarial starts, each run with walks and step by
step under its scheduler; prints a Markdown table (family × scheduler: runs, runs that walked,
mismatches) for docs/VERIFICATION.md and every mismatch in full. Ctrl+C prints what is done.

Run: python scripts/fast_forward_campaign.py [--trials 4000] [--far 10000] [--workers 2]
"""

from __future__ import annotations

import argparse
import multiprocessing
import sys
import time
from collections import Counter

from apf_viz.explore.fast_forward_campaign import SCHEDULERS, Result, Trial, compare, trials
from apf_viz.progress import show_progress


def _compare(trial: Trial) -> Result:
    return compare(trial)


def table(results: list[Result]) -> str:
    runs: Counter[tuple[str, str]] = Counter()
    walked: Counter[tuple[str, str]] = Counter()
    bad: Counter[tuple[str, str]] = Counter()
    for r in results:
        key = (r.trial.case.family, r.trial.scheduler)
        runs[key] += 1
        walked[key] += bool(r.walks or r.forced)
        bad[key] += r.mismatch is not None
    families = sorted({f for f, _ in runs})
    lines = ["| family | " + " | ".join(SCHEDULERS) + " | mismatches |", "|---|" + "---:|" * 6]
    for f in families:
        cells = [f"{runs[f, s]} ({walked[f, s]} walked)" for s in SCHEDULERS]
        lines.append(f"| {f} | " + " | ".join(cells) + f" | {sum(bad[f, s] for s in SCHEDULERS)} |")
    return "\n".join(lines)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--trials", type=int, default=4000)
    ap.add_argument("--first", type=int, default=0, help="the first trial's seed")
    ap.add_argument("--far", type=int, default=10_000, help="how far apart robots may start")
    ap.add_argument("--workers", type=int, default=2)
    args = ap.parse_args()
    results: list[Result] = []
    start = time.perf_counter()
    pool = multiprocessing.Pool(args.workers)
    try:
        for r in pool.imap_unordered(_compare, trials(args.trials, args.first, args.far), chunksize=4):
            results.append(r)
            if r.mismatch:
                show_progress(f"MISMATCH {r.mismatch}: {r.trial.describe()}", last=True)
            elapsed = time.perf_counter() - start
            eta = elapsed / len(results) * (args.trials - len(results))
            line = f"{len(results)}/{args.trials} trials, {elapsed:.0f} s, ETA {eta:.0f} s"
            show_progress(line, last=False)
    except KeyboardInterrupt:
        pool.terminate()
        show_progress(f"interrupted: {len(results)} trials done", last=True)
    else:
        pool.close()
        show_progress(f"{len(results)} trials in {time.perf_counter() - start:.0f} s", last=True)
    pool.join()
    outcomes = Counter(r.outcome for r in results)
    mismatches = [r for r in results if r.mismatch]
    print(table(results))
    print()
    events = sum(r.events for r in results)
    print(
        f"{len(results)} trials (far = {args.far:,}), {events:,} events step by step; "
        f"outcomes {dict(outcomes)}; {sum(bool(r.walks or r.forced) for r in results)} took walks or "
        f"forced cycles; mismatches: {len(mismatches)}"
    )
    for r in mismatches:
        print(f"- {r.mismatch}: {r.trial.describe()}")
    return 1 if mismatches else 0


if __name__ == "__main__":
    sys.exit(main())
