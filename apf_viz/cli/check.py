"""``apf-viz check``: every schedule of a small start (model checking)."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from apf_viz.algorithms import DEFAULT_ALGORITHM
from apf_viz.cli.common import ALGORITHM_HELP, SEMANTICS_HELP, positive, problem, seed

NAME = "check"
HELP = "explore every schedule of a small start (model checking)"
OUTPUTS = ("counterexample",)
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
    p.add_argument("--json", action="store_true", help="print the verdict as one JSON object")
    p.add_argument("--force", action="store_true", help="explore an unsolvable start anyway")
    p.add_argument("--counterexample", type=Path, help="write a failing schedule here as a trace file")


def run(args: argparse.Namespace) -> int:
    from apf_viz.explore.check import all_flips, check, write_counterexample

    robots, points, targets, algorithm = problem(args, args.counterexample)
    flips = all_flips(len(points)) if args.flips == "all" else [tuple(robots.flips(args.seed))]
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
