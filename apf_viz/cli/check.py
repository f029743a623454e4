"""``apf-viz check``: every schedule of a small start (model checking)."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from apf_viz.algorithms import DEFAULT_ALGORITHM
from apf_viz.cli.common import ALGORITHM_HELP, SEMANTICS_HELP, positive, problem, seed

NAME = "check"
HELP = "explore every schedule of a small start (model checking)"
OUTPUTS = ("counterexample", "schedule_out")
WANTED = ("collision", "escape", "deadlock", "livelock")  # explore/explorer.py's WANTED (a test holds them)
"""The options naming files this command writes (never one of its inputs)."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--robots", required=True, type=Path, help="start file (keep k ≤ 5)")
    p.add_argument("--pattern", required=True, type=Path, help="pattern file with one point per robot")
    p.add_argument(
        "--scheduler", default="async", choices=["async", "ssync", "fsync"], help="the adversary explored"
    )
    p.add_argument(
        "--flips",
        default="file",
        choices=["all", "file"],
        help="every assignment of y-axis flips, or the file's (a file without y_up: random from --seed)",
    )
    p.add_argument(
        "--seed", type=seed, default=1, help="seed of the y-axis flips when the robots file gives none"
    )
    p.add_argument(
        "--max-states", type=positive, default=1_000_000, help="stop with verdict 'budget' beyond this"
    )
    p.add_argument("--algorithm", default=DEFAULT_ALGORITHM, help=ALGORITHM_HELP)
    p.add_argument(
        "--light-semantics", default="compute", choices=["compute", "lc-atomic"], help=SEMANTICS_HELP
    )
    p.add_argument(
        "--no-reduction",
        action="store_true",
        help="explore every interleaving (without it, ASYNC skips the orders of invisible events: the same "
        "verdict and counterexample, fewer states; apf-viz docs verification)",
    )
    p.add_argument(
        "--want",
        choices=WANTED,
        help="look for this kind of failure only: the others end their run and the search goes on past "
        "them (verdict 'absent', exit 0, when none exists in any schedule)",
    )
    p.add_argument(
        "--worst",
        choices=("moves", "events"),
        help="the most moves (events) any schedule and flips can force before FORMED, exactly, or why "
        "there is no maximum; --schedule-out writes a schedule that forces it",
    )
    p.add_argument("--schedule-out", type=Path, help="with --worst: write the schedule that forces it here")
    p.add_argument("--json", action="store_true", help="print the verdict as one JSON object")
    p.add_argument("--force", action="store_true", help="explore an unsolvable start anyway")
    p.add_argument("--counterexample", type=Path, help="write a failing schedule here as a trace file")


def run(args: argparse.Namespace) -> int:
    from apf_viz.core.formats import InputError
    from apf_viz.explore.check import all_flips, check, write_counterexample

    if args.schedule_out and not args.worst:
        raise InputError("--schedule-out writes the schedule that forces the worst: give --worst too")
    robots, points, targets, algorithm = problem(args, args.counterexample)
    flips = all_flips(len(points)) if args.flips == "all" else [tuple(robots.flips(args.seed))]
    if args.worst:
        return _worst(args, points, targets, algorithm, flips)
    result, y_up = check(
        algorithm,
        points,
        targets,
        flips,
        args.scheduler,
        args.max_states,
        progress=not args.json,
        light_semantics=args.light_semantics,
        reduction=not args.no_reduction,
        want=args.want,
    )
    written = None
    if result.verdict not in ("verified", "budget", "absent") and args.counterexample:
        write_counterexample(
            args.counterexample,
            algorithm,
            points,
            targets,
            y_up,
            args.scheduler,
            result,
            args.light_semantics,
        )
        written = str(args.counterexample)
    if args.json:
        print(
            json.dumps(
                {
                    "verdict": result.verdict,
                    "want": args.want,
                    "states": result.states,
                    "transitions": result.transitions,
                    "seconds": round(result.seconds, 3),
                    "detail": result.detail,
                    "y_up": list(y_up),
                    "schedule_length": len(result.schedule),
                    "counterexample": written,
                }
            )
        )
    else:
        print(
            f"{result.verdict}: {result.states:,} states, {result.transitions:,} transitions, "
            f"{result.seconds:.2f} s{'; ' + result.detail if result.detail else ''}"
            f"{'; counterexample: ' + written if written else ''}"
        )
    return {"verified": 0, "absent": 0, "budget": 4}.get(result.verdict, 1)


def _worst(args: argparse.Namespace, points, targets, algorithm, flips) -> int:
    """``check --worst``: the maximum, its schedule written and replayed to the same count."""
    from apf_viz.core.budget import paper_D
    from apf_viz.core.files import write_atomic
    from apf_viz.core.formats import InputError
    from apf_viz.explore.check import say_progress
    from apf_viz.explore.worst import worst, worst_schedule_text

    if args.want:
        raise InputError("--worst and --want ask different questions: give one")
    found = worst(
        algorithm, points, targets, flips, args.worst,
        scheduler=args.scheduler, max_states=args.max_states,
        reduction=not args.no_reduction, light_semantics=args.light_semantics,
        progress=None if args.json else say_progress,
    )  # fmt: skip
    written = None
    replayed = None
    if found.verdict == "worst":
        text, moves, events = worst_schedule_text(
            algorithm, points, targets, found, args.scheduler, args.light_semantics
        )
        replayed = moves if args.worst == "moves" else events
        if replayed != found.value:  # never hide it: the maximum is a claim the replay checks
            raise AssertionError(f"the worst schedule replays to {replayed} {args.worst}, not {found.value}")
        if args.schedule_out:
            write_atomic(args.schedule_out, text)
            written = str(args.schedule_out)
    k, d = len(points), paper_D(points, targets)
    if args.json:
        print(json.dumps({
            "verdict": found.verdict, "measure": found.measure, "worst": found.value, "k": k, "D": d,
            "per_kD": round(found.value / (k * d), 4) if found.value is not None else None,
            "states": found.states, "seconds": round(found.seconds, 3), "detail": found.detail,
            "y_up": list(found.y_up), "schedule": written,
        }))  # fmt: skip
    elif found.value is not None:
        print(
            f"worst {found.measure}: {found.value:,} (k·D = {k * d}: {found.value / (k * d):.3f} per k·D), "
            f"over {found.states:,} states, every {args.scheduler.upper()} schedule and "
            f"{len(flips)} flip assignment(s); replayed to {replayed:,}"
            + (f"; schedule: {written}" if written else "")
        )
    else:
        print(f"{found.verdict}: {found.states:,} states, {found.seconds:.2f} s; {found.detail}")
    return {"worst": 0, "budget": 4}.get(found.verdict, 1)
