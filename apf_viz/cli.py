"""The ``apf-viz`` command line.

Exit codes: 0 formed (or success), 1 ran but not formed, 2 bad input, 3 unsolvable start (Theorem 1).
Every error is one line on stderr, never a traceback.
"""

from __future__ import annotations

import argparse
import json
import random
import sys
from collections.abc import Sequence
from dataclasses import asdict
from pathlib import Path
from typing import NoReturn

from apf_viz.algorithms import ALGORITHMS, DEFAULT_ALGORITHM, get_algorithm
from apf_viz.core.engine import Engine
from apf_viz.core.formats import (
    InputError,
    check_sizes,
    load_pattern,
    load_robots,
    load_trace,
    robots_json,
    trace_text,
    write_atomic,
)
from apf_viz.core.frames import random_y_up
from apf_viz.core.run import RunSummary, advance, engine_for_trace, replay, trace_header
from apf_viz.core.schedulers import SCHEDULERS, make_scheduler
from apf_viz.core.symmetry import describe_axis, unsolvable_axis

EXIT_FORMED, EXIT_NOT_FORMED, EXIT_BAD_INPUT, EXIT_UNSOLVABLE = 0, 1, 2, 3
DEFAULT_MAX_EVENTS = 2_000_000


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:
        self.exit(EXIT_BAD_INPUT, f"{self.prog}: error: {message} (see --help)\n")


def _fail(message: str, code: int = EXIT_BAD_INPUT) -> NoReturn:
    print(f"apf-viz: error: {message}", file=sys.stderr)
    raise SystemExit(code)


def _cmd_run(args: argparse.Namespace) -> int:
    robots = load_robots(args.robots)
    pattern = load_pattern(args.pattern)
    check_sizes(robots, pattern, str(args.pattern))
    algorithm = get_algorithm(args.algorithm)
    scheduler = make_scheduler(args.scheduler)
    if scheduler.name == "manual":
        raise InputError("--scheduler manual needs a person to pick robots: use the visualiser")
    points = [tuple(p) for p in robots.robots]
    axis = unsolvable_axis(points)
    if axis is not None and not args.force:
        message = (
            f"{args.robots}: unsolvable start: mirror-symmetric about {describe_axis(axis)}, a horizontal "
            "line through no robot (Theorem 1); --force runs it anyway"
        )
        if args.json:
            print(json.dumps({"outcome": "unsolvable", "axis": float(axis), "message": message}))
        _fail(message, EXIT_UNSOLVABLE)
    y_up = robots.y_up if robots.y_up is not None else random_y_up(len(points), args.seed)
    engine = Engine(
        points,
        [tuple(p) for p in pattern.points],
        algorithm,
        y_up=y_up,
        light_semantics=args.light_semantics,
        max_events=args.max_events,
    )
    advance(engine, scheduler, args.seed)
    summary = RunSummary.of(engine)
    if args.trace:
        header = trace_header(engine, scheduler.name, args.seed)
        write_atomic(args.trace, trace_text(header, engine.history.events()))
    _print_summary(summary, args.json)
    return EXIT_FORMED if summary.outcome == "formed" else EXIT_NOT_FORMED


def _print_summary(summary: RunSummary, as_json: bool) -> None:
    if as_json:
        data = asdict(summary)
        data["final"] = [list(p) for p in summary.final]
        print(json.dumps(data))
    else:
        print(
            f"{summary.outcome}: {summary.events} events, {summary.moves} moves, {summary.cycles} cycles; "
            f"lights used: {', '.join(summary.lights_used)}"
        )


def _cmd_replay(args: argparse.Namespace) -> int:
    header, events = load_trace(args.trace)
    engine = engine_for_trace(header, get_algorithm(header.algorithm))
    replay(engine, events, str(args.trace))
    summary = RunSummary.of(engine)
    _print_summary(summary, args.json)
    return EXIT_FORMED if summary.outcome == "formed" else EXIT_NOT_FORMED


def _cmd_random_robots(args: argparse.Namespace) -> int:
    if args.count < 1 or args.width < 1 or args.height < 1:
        raise InputError("--count, --width and --height must be at least 1")
    if args.count > args.width * args.height:
        raise InputError(f"--count {args.count} robots do not fit in a {args.width}×{args.height} box")
    rng = random.Random(args.seed)
    cells = [(x, y) for x in range(args.width) for y in range(args.height)]
    for _ in range(1000):
        points = sorted(rng.sample(cells, args.count))
        if args.allow_unsolvable or unsolvable_axis(points) is None:
            break
    else:
        raise InputError("could not draw a solvable start in this box; widen it or pass --allow-unsolvable")
    text = robots_json(points)
    if args.out:
        write_atomic(args.out, text)
    else:
        sys.stdout.write(text)
    return 0


def _cmd_check(args: argparse.Namespace) -> int:
    from apf_viz.explore.check import all_flips, check, write_counterexample

    robots = load_robots(args.robots)
    pattern = load_pattern(args.pattern)
    check_sizes(robots, pattern, str(args.pattern))
    algorithm = get_algorithm(args.algorithm)
    points = [tuple(p) for p in robots.robots]
    if args.flips == "all":
        flips = all_flips(len(points))
    else:
        flips = [tuple(robots.y_up) if robots.y_up is not None else (True,) * len(points)]
    result, y_up = check(
        algorithm,
        points,
        [tuple(p) for p in pattern.points],
        flips,
        args.scheduler,
        args.max_states,
        progress=not args.json,
        light_semantics=args.light_semantics,
    )
    written = None
    if result.verdict not in ("verified", "budget") and args.counterexample:
        write_counterexample(
            args.counterexample,
            algorithm,
            points,
            [tuple(p) for p in pattern.points],
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
    return {"verified": 0, "budget": 4}.get(result.verdict, 1)


def _cmd_serve(args: argparse.Namespace) -> int:
    from apf_viz.ui.app import serve  # viser is imported only when the UI is wanted

    return serve(args)


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="apf-viz",
        description=(
            "Interactive workbench for asynchronous opaque luminous robots on the infinite grid. "
            "Without a command it serves the visualiser on a built-in demo."
        ),
        epilog=(
            "Exit codes: 0 formed (check: verified), 1 not formed (check: a violation), 2 bad input, "
            "3 unsolvable start (Theorem 1), 4 check: state budget exhausted."
        ),
    )
    sub = parser.add_subparsers(dest="command", parser_class=_Parser)

    run = sub.add_parser("run", help="run an algorithm headless and report the outcome")
    run.add_argument(
        "--robots", required=True, type=Path, help='start file: {"robots": [[x, y], ...], "y_up": [...]}'
    )
    run.add_argument(
        "--pattern", required=True, type=Path, help='pattern file: {"name": ..., "points": [[x, y], ...]}'
    )
    run.add_argument(
        "--scheduler",
        default="async",
        choices=[s for s in SCHEDULERS if s != "manual"],
        help="the adversary (default: async)",
    )
    run.add_argument(
        "--seed", type=int, default=1, help="seed of the scheduler and of random y flips (default: 1)"
    )
    run.add_argument(
        "--max-events",
        type=int,
        default=DEFAULT_MAX_EVENTS,
        help=f"stop with outcome 'limit' after this many events (default: {DEFAULT_MAX_EVENTS})",
    )
    run.add_argument(
        "--algorithm",
        default=DEFAULT_ALGORITHM,
        help=f"one of {', '.join(ALGORITHMS)}, or module:Name (default: {DEFAULT_ALGORITHM})",
    )
    run.add_argument(
        "--light-semantics",
        default="compute",
        choices=["compute", "lc-atomic"],
        help="when a new light becomes visible: end of Compute (default) or Look+Compute atomic",
    )
    run.add_argument(
        "--json",
        action="store_true",
        help="print one JSON object: outcome, final, moves, events, cycles, lights_used",
    )
    run.add_argument("--trace", type=Path, help="write the run as a JSON Lines trace (atomically)")
    run.add_argument("--force", action="store_true", help="run an unsolvable start anyway")
    run.set_defaults(func=_cmd_run)

    rep = sub.add_parser("replay", help="re-run a trace file exactly and check every event")
    rep.add_argument("--trace", required=True, type=Path)
    rep.add_argument("--json", action="store_true")
    rep.set_defaults(func=_cmd_replay)

    rnd = sub.add_parser("random-robots", help="print a random (solvable) start as a robots file")
    rnd.add_argument("--count", type=int, required=True)
    rnd.add_argument("--width", type=int, required=True)
    rnd.add_argument("--height", type=int, required=True)
    rnd.add_argument("--seed", type=int, default=1)
    rnd.add_argument("--out", type=Path, help="write to this file (atomically) instead of stdout")
    rnd.add_argument("--allow-unsolvable", action="store_true", help="do not redraw symmetric starts")
    rnd.set_defaults(func=_cmd_random_robots)

    chk = sub.add_parser("check", help="explore every schedule of a small start (model checking)")
    chk.add_argument("--robots", required=True, type=Path)
    chk.add_argument("--pattern", required=True, type=Path)
    chk.add_argument("--scheduler", default="async", choices=["async", "ssync", "fsync"])
    chk.add_argument(
        "--flips",
        default="file",
        choices=["all", "file"],
        help="every assignment of y-axis flips, or the file's (default: file; none given = all up)",
    )
    chk.add_argument(
        "--max-states", type=int, default=1_000_000, help="stop with verdict 'budget' beyond this"
    )
    chk.add_argument("--algorithm", default=DEFAULT_ALGORITHM)
    chk.add_argument("--light-semantics", default="compute", choices=["compute", "lc-atomic"])
    chk.add_argument("--json", action="store_true")
    chk.add_argument("--counterexample", type=Path, help="write a failing schedule here as a trace file")
    chk.set_defaults(func=_cmd_check)

    serve = sub.add_parser("serve", help="serve the visualiser (the default command)")
    _add_serve_options(serve)
    serve.set_defaults(func=_cmd_serve)
    return parser


def _add_serve_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--host", default="127.0.0.1", help="address to bind (default: 127.0.0.1)")
    p.add_argument("--port", type=int, default=8080, help="port (default: 8080)")
    p.add_argument("--robots", type=Path, help="start file (default: the built-in demo)")
    p.add_argument("--pattern", type=Path, help="pattern file (default: the built-in demo)")
    p.add_argument("--trace", type=Path, help="replay this trace")
    p.add_argument("--algorithm", default=None, help="algorithm name (default: the demo's)")


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    if not argv or (argv[0].startswith("-") and argv[0] not in ("-h", "--help")):
        argv = ["serve", *argv]  # the visualiser is the default command
    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except InputError as e:
        _fail(str(e))
    except ValueError as e:
        _fail(str(e))
    except OSError as e:
        _fail(f"{e.filename or ''}: {e.strerror}".lstrip(": "))


if __name__ == "__main__":
    sys.exit(main())
