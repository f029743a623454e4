"""``apf-viz adversary``: search for a costly schedule on a start of any size (explore/adversary.py)."""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

from apf_viz.algorithms import DEFAULT_ALGORITHM
from apf_viz.cli.common import (
    ALGORITHM_HELP,
    SEMANTICS_HELP,
    cluster,
    int_within,
    positive,
    problem,
    seed,
    stop_on_sigterm_as_on_ctrl_c,
)
from apf_viz.explore.adversary import WIDTH
from apf_viz.sweeps.driver import duration

NAME = "adversary"
HELP = "search for the costliest schedule an adversary can find (any k): beats the built-in schedulers"


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--robots", required=True, type=Path, help="start file (its flips, else from --seed)")
    p.add_argument("--pattern", required=True, type=Path, help="pattern file with one point per robot")
    p.add_argument(
        "--maximize", choices=("moves", "events"), default="moves", help="what the adversary wants"
    )
    p.add_argument(
        "--budget",
        type=positive,
        default=2_000,
        help="schedules searched (beside the built-in schedulers' runs over seeds 0-19, the bar to beat)",
    )
    p.add_argument(
        "--width", type=int_within(0, 1_000_000, "a width (0 to 1,000,000)"), default=WIDTH,
        help="the widest beam over the adversary's choices: 64, 128, … up to it, until one is never cut "
        "(0: no beam)",
    )  # fmt: skip
    p.add_argument(
        "--seed",
        type=seed,
        default=1,
        help="the search's seed (and the flips', if the file has none: the same as check's and run's)",
    )
    p.add_argument(
        "--schedule-out", type=Path, help="write the costliest schedule found here (replay plays it)"
    )
    p.add_argument("--algorithm", default=DEFAULT_ALGORITHM, help=ALGORITHM_HELP)
    p.add_argument(
        "--light-semantics", default="compute", choices=["compute", "lc-atomic"], help=SEMANTICS_HELP
    )
    p.add_argument(
        "--cluster", type=cluster, help="address of a running Dask scheduler: each batch is tried there"
    )
    p.add_argument("--json", action="store_true", help="print the result as one JSON object")
    p.add_argument("--force", action="store_true", help=argparse.SUPPRESS)


def run(args: argparse.Namespace) -> int:
    """The search, with progress and an ETA on stderr; Ctrl+C keeps the best so far (written, if asked)."""
    from apf_viz.algorithms import get_algorithm
    from apf_viz.core.budget import paper_D
    from apf_viz.core.files import write_atomic
    from apf_viz.core.formats import InputError
    from apf_viz.explore.adversary import Problem, best_schedule_text, evaluate, search

    robots, points, targets, _ = problem(args, args.schedule_out)
    try:
        get_algorithm(args.algorithm)
    except ValueError:
        raise InputError(
            f"--algorithm {args.algorithm}: the searched adversary takes a built-in algorithm"
        ) from None
    p = Problem(
        args.algorithm, tuple(points), tuple(targets), tuple(robots.flips(args.seed)), args.maximize,
        args.light_semantics,
    )  # fmt: skip
    stop_on_sigterm_as_on_ctrl_c()  # keeps the best so far
    evaluator, close = evaluate, lambda: None
    if args.cluster:
        evaluator, close = on_cluster(args.cluster)
    try:
        state = search(
            p, args.budget, args.seed, evaluator, _reporter(args.budget, args.json), width=args.width
        )
    finally:
        close()
        if not args.json:
            print(file=sys.stderr)  # the progress line ends before the answer
    if state.failure is not None:
        return _failed(args, state)
    written = None
    if args.schedule_out:
        write_atomic(args.schedule_out, best_schedule_text(state))
        written = str(args.schedule_out)
    k, d = len(points), paper_D(points, targets)
    best, bar = state.best.value or 0, state.bar.value or 0
    if args.json:
        print(json.dumps({
            "maximize": args.maximize, "found": best, "built_ins": bar, "beats": state.beats,
            "k": k, "D": d, "per_kD": round(best / (k * d), 4), "built_ins_per_kD": round(bar / (k * d), 4),
            "evaluations": state.evaluations, "built_in_runs": state.bar_runs,
            "seconds": round(state.seconds, 2),
            "per_second": round((state.bar_runs + state.evaluations) / max(state.seconds, 1e-9), 2),
            "how": state.best.source, "schedule": written, "exact": state.exact,
        }))  # fmt: skip
    else:
        verdict = "beats" if state.beats else "does not beat"
        print(
            f"found {best:,} {args.maximize} ({best / (k * d):.3f} per k·D, k·D = {k * d}); the built-in "
            f"schedulers' most over seeds 0–19: {bar:,} ({bar / (k * d):.3f}): the search {verdict} them; "
            f"{state.evaluations:,} schedules searched beside the built-ins' {state.bar_runs:,} runs, in "
            f"{duration(state.seconds)}; the best: {state.best.source}"
            + ("; a beam never cut followed every path: this is the exact worst" if state.exact else "")
            + (f"; schedule: {written}" if written else "")
        )
    return 0


def _failed(args: argparse.Namespace, state) -> int:
    """A schedule on which the algorithm fails has no cost to maximize: the failure is the answer, as
    ``check`` reports one (its kind, its schedule written to --schedule-out), exit 1."""
    from apf_viz.core.files import write_atomic
    from apf_viz.explore.adversary import failure_schedule_text

    failure = state.failure
    kind = {"stuck": "deadlock"}.get(failure.outcome, failure.outcome)
    written = None
    if args.schedule_out:
        write_atomic(args.schedule_out, failure_schedule_text(state))
        written = str(args.schedule_out)
    if args.json:
        print(json.dumps({
            "maximize": args.maximize, "found": None, "failure": kind, "events": len(failure.records),
            "how": failure.source, "evaluations": state.evaluations, "built_in_runs": state.bar_runs,
            "seconds": round(state.seconds, 2),
            "schedule": written,
        }))  # fmt: skip
    else:
        print(
            f"{kind}: the algorithm fails under a schedule the search met ({failure.source}, "
            f"{len(failure.records):,} steps): no worst exists"
            + (f"; schedule: {written} (apf-viz run --schedule replays it)" if written else "")
        )
    return 1


def _reporter(budget: int, quiet: bool):
    """Progress on stderr about every second: tried, best, rate and ETA."""

    last = [0.0]

    def report(state) -> None:
        now = time.monotonic()
        if quiet or now - last[0] < 1.0:
            return
        last[0] = now
        if state.doing:
            print(f"\r{state.doing} · {duration(state.seconds)}   ", end="", file=sys.stderr, flush=True)
            return
        rate = state.evaluations / max(state.seconds, 1e-9)
        eta = (budget - state.evaluations) / max(rate, 1e-9)
        print(
            f"\r{state.evaluations:,}/{budget:,} schedules · best {state.best.value:,} "
            f"(built-ins {state.bar.value:,}) · {rate:.1f}/s · ETA {duration(eta)}   ",
            end="", file=sys.stderr, flush=True,
        )  # fmt: skip

    return report


def on_cluster(address: str):
    """An evaluator that tries each batch on the Dask cluster at ``address``, a schedule a task, and the
    way to close it."""
    from apf_viz.explore.adversary import evaluate
    from apf_viz.sweeps.driver import dask_client

    client, _ = dask_client(address, None)

    def evaluator(problem, jobs):
        futures = client.map(lambda job: evaluate(problem, [job])[0], list(jobs), pure=False)
        return client.gather(futures)

    return evaluator, client.close
