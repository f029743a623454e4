"""``apf-viz run``: run an algorithm headless and report the outcome."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from apf_viz.cli.common import (
    EXIT_FORMED,
    EXIT_NOT_FORMED,
    add_run_options,
    fail,
    positive,
    print_summary,
    problem,
)
from apf_viz.core.budget import EVENTS_PER_MOVE, EVENTS_PER_MOVE_PER_ROBOT, MOVES_PER_KD, run_budget
from apf_viz.core.engine import Engine, LightSemantics
from apf_viz.core.files import check_writable, write_atomic
from apf_viz.core.formats import RobotsFile, trace_text
from apf_viz.core.run import RunSummary, advance, trace_header
from apf_viz.core.schedule import (
    Schedule,
    ScheduleError,
    adversary_flips,
    check_robots,
    follow,
    load_schedule,
    schedule_of_steps,
    schedule_text,
)
from apf_viz.core.schedulers import AUTOMATIC, DEFAULT_SCHEDULER, make_scheduler

NAME = "run"
HELP = "run an algorithm headless and report the outcome"
OUTPUTS = ("trace", "schedule_out")
"""The options naming files this command writes (never one of its inputs)."""


def _schedule_adversary(args: argparse.Namespace, robots: RobotsFile, schedule: Schedule):
    """The flips and light semantics of a run that follows a schedule: the schedule's own, whatever
    --seed says; a contradiction with the robots file or --light-semantics is refused."""
    check_robots(schedule, len(robots.robots), str(args.schedule))  # before any warning about its flips
    y_up, warning = adversary_flips(schedule, robots.y_up, args.flips, str(args.schedule), str(args.robots))
    if warning:
        print(f"apf-viz: warning: {warning}", file=sys.stderr)
    semantics: LightSemantics = schedule.light_semantics or args.light_semantics or "compute"
    if args.light_semantics and schedule.light_semantics and args.light_semantics != semantics:
        fail(
            f"--light-semantics {args.light_semantics} contradicts {args.schedule}, recorded under "
            f"{schedule.light_semantics} (leave the option out to follow the schedule)"
        )
    return (list(y_up) if y_up is not None else robots.flips(args.seed)), semantics


def _write_outputs(args: argparse.Namespace, engine: Engine, adversary: str) -> None:
    if args.trace:
        header = trace_header(engine, adversary, args.seed)
        write_atomic(args.trace, trace_text(header, engine.history.events()))
    if args.schedule_out:
        lines = schedule_of_steps(engine.history.steps)
        text = schedule_text(engine.k, lines, engine.y_up, engine.light_semantics)
        write_atomic(args.schedule_out, text)


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--robots", required=True, type=Path, help='start file: {"robots": [[x, y], ...], "y_up": [...]}'
    )
    p.add_argument(
        "--pattern", required=True, type=Path, help='pattern file: {"name": ..., "points": [[x, y], ...]}'
    )
    add_run_options(p, list(AUTOMATIC), defaults=False)
    _add_limits(p)
    p.add_argument(
        "--json",
        action="store_true",
        help="print one JSON object: outcome, final, k, D, moves, events, cycles, skipped, "
        "moves_per_kD, max_moves, max_events, lights_used",
    )
    p.add_argument("--trace", type=Path, help="write every event to this JSON Lines file (atomically)")
    _add_schedule_options(p)
    p.add_argument("--force", action="store_true", help="run an unsolvable start anyway")


def _add_limits(p: argparse.ArgumentParser) -> None:
    """The run's caps, and how its events are applied."""
    p.add_argument(
        "--max-events",
        type=positive,
        help="stop with outcome 'limit' at this many events, never past them under any scheduler or light "
        "semantics (a step that would pass them, such as a round of several robots, is not taken) (default: "
        "the run's budget, "
        f"{EVENTS_PER_MOVE} per budgeted move, or {EVENTS_PER_MOVE} + {EVENTS_PER_MOVE_PER_ROBOT}·k with "
        "--all-activations)",
    )
    p.add_argument(
        "--max-moves",
        type=positive,
        help=f"stop with outcome 'limit' after this many moves (default: the budget, {MOVES_PER_KD}·k·D)",
    )
    p.add_argument(
        "--all-activations",
        action="store_true",
        help="keep every activation, also the cycles that change nothing (by default the scheduler "
        "passes over a robot whose view it would answer with 'same light, stay')",
    )
    p.add_argument(
        "--no-fast-forward",
        action="store_true",
        help="apply every event one by one (by default, where the scheduler has no choice, a lone robot's "
        "repeating cycles are applied as one walk: the same run, event for event, much faster when robots "
        "are far apart; never with --all-activations or a --schedule)",
    )
    p.add_argument(
        "--check-walks",
        action="store_true",
        help="re-decide every step a walk skips, on views built from scratch, and stop with exit code 5 "
        "on a difference (slow: a check of fast-forward; also APF_VIZ_CHECK_WALKS=1)",
    )


def _add_schedule_options(p: argparse.ArgumentParser) -> None:
    """A schedule to follow instead of a scheduler, and the run's own schedule to write."""
    p.add_argument(
        "--schedule",
        type=Path,
        help="follow this schedule file (who acts, line by line, and each robot's y-axis; apf-viz docs cli, "
        "'Playing the adversary') instead of --scheduler; it replays the run it was recorded from "
        "whatever --seed says; the run stops where it ends (outcome schedule-end) unless --then",
    )
    p.add_argument(
        "--flips",
        choices=["schedule", "file"],
        help="with --schedule, when the robots file states y_up and it differs from the schedule's flips: "
        "which to use (without it the contradiction is refused)",
    )
    p.add_argument(
        "--then",
        choices=list(AUTOMATIC),
        help="with --schedule: when the schedule ends, continue under this scheduler",
    )
    p.add_argument(
        "--schedule-out",
        type=Path,
        help="write the run's schedule (who acted, the flips, the light semantics) to this file (atomically)",
    )


def run(args: argparse.Namespace) -> int:
    robots, points, targets, algorithm = problem(args, args.trace)
    if args.schedule_out:
        check_writable(args.schedule_out)
    if args.then and not args.schedule:
        fail("--then continues after a --schedule: give one")
    if args.flips and not args.schedule:
        fail("--flips chooses between a --schedule's flips and the robots file's: give a schedule")
    if args.schedule and args.scheduler:
        fail(
            f"--schedule is the adversary, so --scheduler {args.scheduler} would be ignored; to continue "
            f"under a scheduler where the schedule ends, give --then {args.scheduler}"
        )
    schedule = load_schedule(args.schedule) if args.schedule else None
    y_up = robots.flips(args.seed)
    semantics: LightSemantics = args.light_semantics or "compute"
    if schedule is not None:
        y_up, semantics = _schedule_adversary(args, robots, schedule)
    then = make_scheduler(args.then) if args.then else None
    scheduler = make_scheduler(args.scheduler or DEFAULT_SCHEDULER)
    skip = not args.all_activations
    budget = run_budget(points, targets, skip)  # a cap given on the command line replaces its part
    engine = Engine(
        points,
        targets,
        algorithm,
        y_up=y_up,
        light_semantics=semantics,
        max_events=args.max_events or budget.max_events,
        max_moves=args.max_moves or budget.max_moves,
        skip_noops=skip,
        fast_forward=not args.no_fast_forward,
        check_walks=args.check_walks or None,
    )
    outcome = None
    if schedule is not None:
        try:
            for _ in follow(engine, schedule, str(args.schedule)):
                pass
        except ScheduleError:
            _write_outputs(args, engine, "schedule")  # the run so far is kept
            raise
        if not engine.finished and then is None:
            outcome = "schedule-end"
        elif then is not None:
            advance(engine, then, args.seed)
    else:
        advance(engine, scheduler, args.seed)
    summary = RunSummary.of(engine, outcome)
    _write_outputs(args, engine, scheduler.name if schedule is None else "schedule")
    print_summary(summary, args.json)
    return EXIT_FORMED if summary.outcome == "formed" else EXIT_NOT_FORMED
