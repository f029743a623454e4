"""The ``apf-viz`` command line.

Exit codes: 0 formed (or success), 1 ran but not formed, 2 bad input, 3 unsolvable start (Theorem 1).
Every error is one line on stderr, never a traceback.
"""

from __future__ import annotations

import argparse
import json
import re
import sys
import time
from collections.abc import Sequence
from dataclasses import asdict
from pathlib import Path
from typing import NoReturn

from apf_viz.algorithms import ALGORITHMS, DEFAULT_ALGORITHM, algorithm_from_command_line, get_algorithm
from apf_viz.core import shapes
from apf_viz.core.budget import EVENTS_PER_MOVE, EVENTS_PER_MOVE_PER_ROBOT, MOVES_PER_KD, run_budget
from apf_viz.core.engine import Engine
from apf_viz.core.fast_forward import WalkMismatch
from apf_viz.core.formats import (
    MAX_INPUT_BYTES,
    InputError,
    RobotsFile,
    check_sizes,
    check_writable,
    load_pattern,
    load_robots,
    load_trace,
    pattern_json,
    read_text,
    robots_json,
    trace_text,
    write_atomic,
)
from apf_viz.core.pattern_match import matches_pattern
from apf_viz.core.random_configs import random_pattern, random_robots
from apf_viz.core.run import RunSummary, advance, engine_for_trace, replay, trace_header
from apf_viz.core.schedule import (
    Schedule,
    ScheduleError,
    adversary_flips,
    check_robots,
    follow,
    load_schedule,
    schedule_of_steps,
    schedule_of_trace,
    schedule_text,
)
from apf_viz.core.schedulers import SCHEDULERS, make_scheduler
from apf_viz.core.symmetry import describe_axis, unsolvable_axis

EXIT_FORMED, EXIT_NOT_FORMED, EXIT_BAD_INPUT, EXIT_UNSOLVABLE = 0, 1, 2, 3
EXIT_WALK_MISMATCH = 5  # --check-walks found a walk that is not the step-by-step run


class _Parser(argparse.ArgumentParser):
    """One-line errors (exit 2), and no abbreviations: ``--robot`` is a typo, not ``--robots``."""

    def __init__(self, *args, **kwargs) -> None:
        kwargs.setdefault("allow_abbrev", False)
        super().__init__(*args, **kwargs)

    def error(self, message: str) -> NoReturn:
        self.exit(EXIT_BAD_INPUT, f"{self.prog}: error: {message} (see --help)\n")


def _fail(message: str, code: int = EXIT_BAD_INPUT) -> NoReturn:
    print(f"apf-viz: error: {message}", file=sys.stderr)
    raise SystemExit(code)


def _int_within(low: int, high: float, what: str):
    """An argparse type: an integer from ``low`` to ``high``, else "… is not ``what``"."""

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not {what}") from None
        if not low <= value <= high:
            raise argparse.ArgumentTypeError(f"{value} is not {what}")
        return value

    return parse


_positive = _int_within(1, float("inf"), "a positive integer")


# A local worker is a process of its own (about 100 MB with its imports): more than this per core only
# queue behind each other, and 100,000 of them would never start.
WORKERS_PER_CORE = 4
_CLUSTER = re.compile(r"((tcp|tls|ws|wss|ucx)://)?(\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9.-]+):[0-9]{1,5}")


def _workers(text: str) -> int:
    """An argparse type: local worker processes, at most ``WORKERS_PER_CORE`` per core of this machine."""
    from apf_viz.sweep import usable_cores

    n = _positive(text)
    most = WORKERS_PER_CORE * usable_cores()
    if n > most:
        raise argparse.ArgumentTypeError(
            f"{n:,} local worker processes: this machine can run at most {most} ({WORKERS_PER_CORE} per "
            "core); for more, start a Dask cluster and give --cluster"
        )
    return n


def _cluster(text: str) -> str:
    """An argparse type: a Dask scheduler's network address (``tcp://HOST:PORT``; an in-process
    address names nothing another process can reach)."""
    if not _CLUSTER.fullmatch(text):
        raise argparse.ArgumentTypeError(
            f"{text!r} is not a Dask scheduler's address: give tcp://HOST:PORT (or tls://, ws://, wss://)"
        )
    return text


def _positive_seconds(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number of seconds") from None
    if not 0 < value < float("inf"):
        raise argparse.ArgumentTypeError(f"{text} is not a positive number of seconds")
    return value


_port = _int_within(0, 65535, "a port (0 to 65535)")


def _refuse_unsolvable(robots_path: Path, points: list, targets: list, as_json: bool) -> None:
    """Theorem 1: a start mirror-symmetric about a robot-free horizontal line cannot form any pattern
    (unless it already is the pattern). Exit 3, naming the axis."""
    axis = unsolvable_axis(points)
    if axis is None or matches_pattern(points, targets):
        return
    message = (
        f"{robots_path}: unsolvable start: mirror-symmetric about {describe_axis(axis)}, a horizontal "
        "line through no robot (Theorem 1); --force runs it anyway"
    )
    if as_json:
        print(json.dumps({"outcome": "unsolvable", "axis": float(axis), "message": message}))
    _fail(message, EXIT_UNSOLVABLE)


def _problem(args: argparse.Namespace, output: Path | None):
    """What ``run`` and ``check`` start from: the robots file, its points, the pattern's points and the
    algorithm, every input checked (and the output path, before any work) with one-line errors."""
    robots = load_robots(args.robots)
    pattern = load_pattern(args.pattern)
    check_sizes(robots, pattern, str(args.pattern))
    algorithm, _ = algorithm_from_command_line(args.algorithm)
    if output:
        check_writable(output)  # before the work, not after minutes of it
    points = [tuple(p) for p in robots.robots]
    targets = [tuple(p) for p in pattern.points]
    if not args.force:
        _refuse_unsolvable(args.robots, points, targets, args.json)
    return robots, points, targets, algorithm


def _cmd_run(args: argparse.Namespace) -> int:
    robots, points, targets, algorithm = _problem(args, args.trace)
    if args.schedule_out:
        check_writable(args.schedule_out)
    if args.then and not args.schedule:
        _fail("--then continues after a --schedule: give one")
    if args.flips and not args.schedule:
        _fail("--flips chooses between a --schedule's flips and the robots file's: give a schedule")
    if args.schedule and args.scheduler:
        _fail(
            f"--schedule is the adversary, so --scheduler {args.scheduler} would be ignored; to continue "
            f"under a scheduler where the schedule ends, give --then {args.scheduler}"
        )
    schedule = load_schedule(args.schedule) if args.schedule else None
    y_up, semantics = robots.flips(args.seed), args.light_semantics or "compute"
    if schedule is not None:
        y_up, semantics = _schedule_adversary(args, robots, schedule)
    then = make_scheduler(args.then) if args.then else None
    scheduler = make_scheduler(args.scheduler or "async")
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
    _print_summary(summary, args.json)
    return EXIT_FORMED if summary.outcome == "formed" else EXIT_NOT_FORMED


def _schedule_adversary(args: argparse.Namespace, robots: RobotsFile, schedule: Schedule):
    """The flips and light semantics of a run that follows a schedule: the schedule's own, whatever
    --seed says; a contradiction with the robots file or --light-semantics is refused."""
    check_robots(schedule, len(robots.robots), str(args.schedule))  # before any warning about its flips
    y_up, warning = adversary_flips(schedule, robots.y_up, args.flips, str(args.schedule), str(args.robots))
    if warning:
        print(f"apf-viz: warning: {warning}", file=sys.stderr)
    semantics = schedule.light_semantics or args.light_semantics or "compute"
    if args.light_semantics and schedule.light_semantics and args.light_semantics != semantics:
        _fail(
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


def _need_extra(command: str, modules: Sequence[str]) -> None:
    """Refuse in one line, before any work, a command whose optional packages are not installed."""
    import importlib.util

    missing = [m for m in modules if importlib.util.find_spec(m) is None]
    if missing:
        _fail(
            f"apf-viz {command} needs the sweep extra ({', '.join(missing)} is not installed): "
            "pip install 'apf-viz[sweep]' (or, in a checkout, pip install -e '.[sweep]')"
        )


def _cmd_sweep(args: argparse.Namespace) -> int:
    _need_extra("sweep", ["dask", "distributed", "pyarrow"])
    from apf_viz import sweep

    if args.out.suffix not in (".parquet", ".csv"):
        _fail(f"--out {args.out}: write .parquet or .csv")
    cells = sweep.grid(
        sweep.parse_range(args.ks, "--ks"),
        sweep.parse_range(args.seeds, "--seeds"),
        [s.strip() for s in args.schedulers.split(",")],
        [a.strip() for a in args.algorithms.split(",")],
        [s.strip() for s in args.light_semantics.split(",")],
        args.starts,
    )
    check_writable(args.out)
    try:
        rows = sweep.run_sweep(
            cells,
            args.out,
            traces=args.traces,
            workers=args.workers,
            cluster=args.cluster,
            progress=sweep.report_progress,
            run_timeout=args.run_timeout,
        )
    except KeyboardInterrupt:
        return 130
    print(sweep.summary(rows))
    return 0


def _cmd_lights(args: argparse.Namespace) -> int:
    _need_extra("lights", ["dask", "distributed", "pyarrow"])
    from apf_viz import lights

    if args.out.suffix != ".parquet":
        _fail(f"--out {args.out}: the lab writes a .parquet table")
    if not 0 <= args.random <= lights.MAX_RANDOM_RUNS:
        _fail(f"--random {args.random:,}: a number of runs per merge, from 0 to {lights.MAX_RANDOM_RUNS:,}")
    chosen = lights.merges(args.algorithm, args.merges)
    ks = lights.parse_ks(args.ks)
    t0 = time.perf_counter()
    try:
        rows = lights.run_lab(
            chosen,
            ks,
            args.out,
            random_runs=args.random,
            traces=args.traces,
            workers=args.workers,
            cluster=args.cluster,
            progress=lights.report_progress,
        )
    except KeyboardInterrupt:
        return 130
    names = {m.name for m in chosen}
    print(lights.summary([r for r in rows if r["merge"] in names and r["ks"] == lights.ks_label(ks)]))
    print(f"{time.perf_counter() - t0:.0f} s", file=sys.stderr)
    return 0


def _cmd_plot(args: argparse.Namespace) -> int:
    _need_extra("plot", ["matplotlib", "pyarrow"])
    from apf_viz import lights, plot, sweep

    if not args.results.is_file():
        _fail(f"{args.results}: no such file")
    if args.results.suffix == ".parquet" and lights.is_lights_table(args.results):
        written = [plot.plot_lights(lights.read_lights(args.results), args.out)]
    else:
        written = plot.plot(sweep.read_results(args.results), args.out)
    for path in written:
        print(path)
    return 0


def _cmd_schedule(args: argparse.Namespace) -> int:
    for out in (args.out, args.robots_out, args.pattern_out):
        if out:
            check_writable(out)  # before reading a trace of a million lines, not after
    header, events = load_trace(args.from_trace)
    lc_atomic = header.light_semantics == "lc-atomic"
    y_up = header.y_up if header.y_up is not None else [True] * len(header.robots)  # as the replay does
    text = schedule_text(
        len(header.robots), schedule_of_trace(events, lc_atomic), y_up, header.light_semantics
    )
    if args.robots_out:
        write_atomic(args.robots_out, robots_json(header.robots, y_up))
    if args.pattern_out:
        write_atomic(args.pattern_out, pattern_json(header.pattern, f"pattern of {args.from_trace.name}"))
    _emit(text, args.out)
    return 0


def _print_summary(summary: RunSummary, as_json: bool) -> None:
    if as_json:
        data = asdict(summary)
        data["final"] = [list(p) for p in summary.final]
        print(json.dumps(data))
    else:
        limit = ""
        if summary.outcome == "limit":
            limit = f" (the run's cap: {summary.max_moves:,} moves or {summary.max_events:,} events)"
        print(
            f"{summary.outcome}{limit}: {summary.events} events, {summary.moves} moves "
            f"(moves/(k·D) = {summary.moves_per_kD:.3f}), {summary.cycles} cycles, {summary.skipped} "
            f"robot·steps passed over; lights used: {', '.join(summary.lights_used)}"
        )


def _cmd_replay(args: argparse.Namespace) -> int:
    header, events = load_trace(args.trace)
    if args.algorithm:
        algorithm, _ = algorithm_from_command_line(args.algorithm)
    else:
        try:
            algorithm = get_algorithm(header.algorithm)  # a file names built-in algorithms only
        except ValueError as e:
            raise InputError(
                f"{args.trace}: {e}; to replay it with an algorithm of your own, pass --algorithm"
            ) from None
    engine = engine_for_trace(header, algorithm)
    replay(engine, events, str(args.trace))
    summary = RunSummary.of(engine)
    _print_summary(summary, args.json)
    if summary.outcome == "running" and not args.json:
        print(f"apf-viz: the trace ends after {summary.events} events, before the run does", file=sys.stderr)
    return EXIT_FORMED if summary.outcome == "formed" else EXIT_NOT_FORMED


def _emit(text: str, out: Path | None) -> None:
    if out:
        write_atomic(out, text)
    else:
        sys.stdout.write(text)


def _cmd_random_robots(args: argparse.Namespace) -> int:
    if args.out:
        check_writable(args.out)
    points = random_robots(
        args.count, args.width, args.height, args.seed, allow_unsolvable=args.allow_unsolvable
    )
    _emit(robots_json(points), args.out)
    return 0


def _cmd_random_pattern(args: argparse.Namespace) -> int:
    if args.out:
        check_writable(args.out)
    _emit(pattern_json(random_pattern(args.count, args.width, args.height, args.seed), args.name), args.out)
    return 0


SHAPES = {
    "ring": lambda n: shapes.ring((0, 0), n),
    "disc": lambda n: shapes.disc((0, 0), n),
    "box": lambda n: shapes.box((0, 0), (n - 1, n - 1)),
    "outline": lambda n: shapes.outline((0, 0), (n - 1, n - 1)),
    "row": lambda n: shapes.row((0, 0), n),
    "column": lambda n: shapes.column((0, 0), n),
    "staircase": lambda n: shapes.staircase((0, 0), n),
}
# The least --size of each shape: a ring or a disc of radius 0 is one cell; a box of side 0 is nothing
# (and a side below 0 would be read as a box the other way round).
_LEAST_SIZE = {"ring": 0, "disc": 0}


def _cmd_pattern(args: argparse.Namespace) -> int:
    """A drawing made from a specification, then mirrored, turned, scaled and fitted in that order."""
    if args.out:
        check_writable(args.out)
    if args.text is not None:
        cells = shapes.text(args.text, (0, 0))
        if not cells:
            _fail(f"--text {args.text!r}: no cells to draw (only spaces)")
    elif args.ascii is not None:
        lines = read_text(args.ascii, MAX_INPUT_BYTES).splitlines()
        try:
            cells = shapes.ascii_art(lines)
        except shapes.ShapeError as e:
            raise InputError(f"{args.ascii}: {e}") from None
        if not cells:
            raise InputError(f"{args.ascii}: no '#' cell in it")
    else:
        least = _LEAST_SIZE.get(args.shape, 1)
        if not least <= args.size <= shapes.MAX_SIZE:
            _fail(f"--shape {args.shape} --size {args.size}: choose a whole number from {least} to "
                  f"{shapes.MAX_SIZE:,}")  # fmt: skip
        cells = SHAPES[args.shape](args.size)
    for axis in args.mirror:
        cells = shapes.mirrored(cells, axis)
    for _ in range(args.rotate):
        cells = shapes.rotated(cells)
    cells = shapes.scaled(cells, args.scale)
    if args.count is not None:
        cells, said = shapes.fitted(cells, args.count)
        print(f"apf-viz pattern: fit to {args.count}: {said}", file=sys.stderr)
    if args.kind == "robots":
        axis = unsolvable_axis(cells)
        if axis is not None:
            note = f"these robots are unsolvable (Theorem 1: mirror axis {describe_axis(axis)})"
            print(f"apf-viz pattern: note: {note}", file=sys.stderr)
        _emit(robots_json(cells), args.out)
    else:
        _emit(pattern_json(cells, args.name or args.text), args.out)
    return 0


def _cmd_check(args: argparse.Namespace) -> int:
    from apf_viz.explore.check import all_flips, check, write_counterexample

    robots, points, targets, algorithm = _problem(args, args.counterexample)
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
    )
    written = None
    if result.verdict not in ("verified", "budget") and args.counterexample:
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


def _cmd_lecture(args: argparse.Namespace) -> int:
    """Every stop of the lecture in order, headless: its condition met or not, at which event; exit 1 if
    any was not (a lecturer checks the evening before)."""
    from apf_viz.lecture import find_lecture
    from apf_viz.ui.lecturer import Lecturer
    from apf_viz.ui.session import Session

    lecture = find_lecture(args.file)
    print(f"{args.file}: {lecture.title} — {len(lecture.stops)} stops", flush=True)
    failed = 0
    blank = Session([(0, 0)], [(0, 0)])  # the first stop loads its scenario (no viser is imported)
    for reached in Lecturer(blank, lecture).check():
        stop = lecture.stops[reached.index]
        where = "its scenario's start" if stop.scenario else "where the stop before left the run"
        until = stop.until.describe() if stop.until else where
        mark = "ok " if reached.holds else "NOT"
        note = f" — {reached.note}" if reached.note else ""
        claims = stop.expect.count() if stop.expect else 0
        said = f"; {claims} claim(s) hold" if claims and not reached.broken else ""
        span = f"to {until}; event {reached.event}{said}"
        print(f"  {mark} stop {reached.index + 1}: {stop.title} ({span}){note}")
        for broken in reached.broken:
            print(f"      {broken}")
        print(f"      shows: {reached.shown}")
        failed += not reached.holds
    held = len(lecture.stops) - failed
    print(f"{held} of {len(lecture.stops)} stops reached, their claims true", flush=True)
    return EXIT_NOT_FORMED if failed else 0


def _cmd_serve(args: argparse.Namespace) -> int:
    from apf_viz.ui.app import serve  # viser is imported only when the UI is wanted

    return serve(args)


class _HelpFormatter(argparse.HelpFormatter):
    """Every option's help ends with its default, when it has one worth showing."""

    def _get_help_string(self, action: argparse.Action) -> str:
        text = action.help or ""
        default = action.default
        if "%(default)" in text or default in (None, False, argparse.SUPPRESS) or not action.option_strings:
            return text
        return f"{text} (default: %(default)s)"


ALGORITHM_HELP = (
    f"the algorithm: {', '.join(ALGORITHMS)}; apf-opaque-grid@R1,R2 for exactly these resolutions "
    "(docs/ALGORITHM.md); or package.module:Name for your own"
)
SEMANTICS_HELP = "when a new light becomes visible: at the end of Compute, or Look+Compute atomic"


def _add_run_options(p: argparse.ArgumentParser, schedulers: Sequence[str], defaults: bool = True) -> None:
    """The adversary's options. ``defaults=False`` (``run``) leaves --scheduler and --light-semantics
    None when not given, so that a --schedule can tell them apart from the defaults."""
    p.add_argument(
        "--scheduler",
        default="async" if defaults else None,
        choices=list(schedulers),
        help="the adversary" + ("" if defaults else " (default: async)"),
    )
    p.add_argument(
        "--seed",
        type=int,
        default=1,
        help="seed of the scheduler, and of the y-axis flips when the robots file gives none",
    )
    p.add_argument("--algorithm", default=DEFAULT_ALGORITHM, help=ALGORITHM_HELP)
    p.add_argument(
        "--light-semantics",
        default="compute" if defaults else None,
        choices=["compute", "lc-atomic"],
        help=SEMANTICS_HELP + ("" if defaults else " (default: compute, or the --schedule's)"),
    )


def _add_box_options(p: argparse.ArgumentParser, what: str) -> None:
    p.add_argument("--count", type=int, required=True, help=f"number of {what}")
    p.add_argument("--width", type=int, required=True, help="the box is x = 0 .. width-1")
    p.add_argument("--height", type=int, required=True, help="the box is y = 0 .. height-1")
    p.add_argument("--seed", type=int, default=1, help="the same seed draws the same points")
    p.add_argument("--out", type=Path, help="write to this file (atomically) instead of standard output")


def _add_pattern_options(p: argparse.ArgumentParser) -> None:
    """``apf-viz pattern``: one source (text, ASCII art, a shape), then the transforms in order."""
    source = p.add_mutually_exclusive_group(required=True)
    source.add_argument("--text", help="letters A-Z, digits and spaces in a 3x5 font")
    source.add_argument("--ascii", type=Path, help="a text file: '#' is a cell, the first line the top row")
    source.add_argument(
        "--shape", choices=list(SHAPES), help="a shape of --size (a ring's radius, a row's length)"
    )
    p.add_argument("--size", type=int, default=4, help="the shape's radius, length, steps or side")
    p.add_argument(
        "--mirror",
        choices=["x", "y"],
        action="append",
        default=[],
        help="mirror left-right (x) or up-down (y)",
    )
    p.add_argument("--rotate", type=int, choices=[0, 1, 2, 3], default=0, help="quarter turns anticlockwise")
    p.add_argument(
        "--scale", type=int, choices=[1, 2, 3, 4], default=1, help="each cell a scale x scale block"
    )
    p.add_argument(
        "--count",
        type=int,
        help="fit to this many cells: the last drawn removed, or cells added along the outline",
    )
    p.add_argument(
        "--as", dest="kind", choices=["pattern", "robots"], default="pattern", help="the file to write"
    )
    p.add_argument("--name", help="the pattern's name in the file")
    p.add_argument("--out", type=Path, help="write to this file (atomically) instead of standard output")
    p.set_defaults(func=_cmd_pattern)


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="apf-viz",
        formatter_class=_HelpFormatter,
        description=(
            "Interactive workbench for asynchronous opaque luminous robots on the infinite grid. "
            "Without a command it serves the visualiser on a built-in demo."
        ),
        epilog=(
            "Exit codes: 0 formed (check: verified), 1 not formed (check: a violation), 2 bad input, "
            "3 unsolvable start (Theorem 1), 4 check: state budget exhausted, 5 run --check-walks: a walk "
            "that is not the step-by-step run."
        ),
    )
    sub = parser.add_subparsers(dest="command", parser_class=_Parser)

    def command(name: str, text: str) -> argparse.ArgumentParser:
        return sub.add_parser(name, help=text, description=text, formatter_class=_HelpFormatter)

    run = command("run", "run an algorithm headless and report the outcome")
    run.add_argument(
        "--robots", required=True, type=Path, help='start file: {"robots": [[x, y], ...], "y_up": [...]}'
    )
    run.add_argument(
        "--pattern", required=True, type=Path, help='pattern file: {"name": ..., "points": [[x, y], ...]}'
    )
    _add_run_options(run, [s for s in SCHEDULERS if s != "manual"], defaults=False)
    run.add_argument(
        "--max-events",
        type=_positive,
        help="stop with outcome 'limit' at this many events, never past them (under lc-atomic, where a "
        "Look is two events, possibly one short) (default: the run's budget, "
        f"{EVENTS_PER_MOVE} per budgeted move, or {EVENTS_PER_MOVE} + {EVENTS_PER_MOVE_PER_ROBOT}·k with "
        "--all-activations)",
    )
    run.add_argument(
        "--max-moves",
        type=_positive,
        help=f"stop with outcome 'limit' after this many moves (default: the budget, {MOVES_PER_KD}·k·D)",
    )
    run.add_argument(
        "--all-activations",
        action="store_true",
        help="keep every activation, also the cycles that change nothing (by default the scheduler "
        "passes over a robot whose view it would answer with 'same light, stay')",
    )
    run.add_argument(
        "--no-fast-forward",
        action="store_true",
        help="apply every event one by one (by default, where the scheduler has no choice, a lone robot's "
        "repeating cycles are applied as one walk: the same run, event for event, much faster when robots "
        "are far apart; never with --all-activations or a --schedule)",
    )
    run.add_argument(
        "--check-walks",
        action="store_true",
        help="re-decide every step a walk skips, on views built from scratch, and stop with exit code 5 "
        "on a difference (slow: a check of fast-forward; also APF_VIZ_CHECK_WALKS=1)",
    )
    run.add_argument(
        "--json",
        action="store_true",
        help="print one JSON object: outcome, final, k, D, moves, events, cycles, skipped, "
        "moves_per_kD, max_moves, max_events, lights_used",
    )
    run.add_argument("--trace", type=Path, help="write every event to this JSON Lines file (atomically)")
    run.add_argument(
        "--schedule",
        type=Path,
        help="follow this schedule file (who acts, line by line, and each robot's y-axis; README 'Playing "
        "the adversary') instead of --scheduler; it replays the run it was recorded from whatever --seed "
        "says; the run stops where it ends (outcome schedule-end) unless --then",
    )
    run.add_argument(
        "--flips",
        choices=["schedule", "file"],
        help="with --schedule, when the robots file states y_up and it differs from the schedule's flips: "
        "which to use (without it the contradiction is refused)",
    )
    run.add_argument(
        "--then",
        choices=[s for s in SCHEDULERS if s != "manual"],
        help="with --schedule: when the schedule ends, continue under this scheduler",
    )
    run.add_argument(
        "--schedule-out",
        type=Path,
        help="write the run's schedule (who acted, the flips, the light semantics) to this file (atomically)",
    )
    run.add_argument("--force", action="store_true", help="run an unsolvable start anyway")
    run.set_defaults(func=_cmd_run)

    swp = command("sweep", "run a grid of runs on Dask into one results table (docs/SWEEPS.md)")
    swp.add_argument(
        "--ks", default="5,10,20", help="robot counts: a list and/or ranges, e.g. 5,10,20 or 3-6"
    )
    swp.add_argument("--seeds", default="1-10", help="seeds: e.g. 1-50 (each seed gives its own start)")
    swp.add_argument("--schedulers", default="async", help="comma-separated schedulers")
    swp.add_argument("--algorithms", default=DEFAULT_ALGORITHM, help="comma-separated algorithm names")
    swp.add_argument("--light-semantics", default="compute", help="comma-separated: compute, lc-atomic")
    swp.add_argument(
        "--starts", type=Path, help="a folder of NAME.robots.json + NAME.pattern.json pairs instead of --ks"
    )
    swp.add_argument(
        "--out", type=Path, required=True, help="results.parquet or results.csv (resumed if present)"
    )
    swp.add_argument("--traces", type=Path, help="write a trace of every run that did not form here")
    swp.add_argument("--workers", type=_workers, help="local worker processes (default: one per core)")
    swp.add_argument(
        "--cluster", type=_cluster, help="address of a running Dask scheduler, e.g. tcp://host:8786"
    )
    swp.add_argument(
        "--run-timeout",
        type=_positive_seconds,
        help="seconds one run may take; a run past it is recorded as outcome 'timeout' with its counts "
        "so far, and the sweep goes on (default: no limit)",
    )
    swp.set_defaults(func=_cmd_sweep)

    lab = command("lights", "which lights could be one colour? every merge of two, explored (docs/LIGHTS.md)")
    lab.add_argument("--algorithm", default=DEFAULT_ALGORITHM, help="the algorithm whose lights are merged")
    lab.add_argument(
        "--ks",
        default="1-5",
        help="robots the explorer covers: 1–3 every start of a 4×4 box, 4–5 the stated starts",
    )
    lab.add_argument("--merges", help="only these merges, e.g. leader1=decider,off=call (default: every one)")
    lab.add_argument(
        "--random",
        type=int,
        default=0,
        help="random runs (half of k = 6–12 random robots, half on the Demo starts) for each merge the "
        "explorer could not break",
    )
    lab.add_argument(
        "--out", required=True, type=Path, help="the verdicts table (.parquet), resumed if there"
    )
    lab.add_argument("--traces", type=Path, help="counterexample traces here (default: OUT's name + -traces)")
    lab.add_argument("--workers", type=_workers, help="local worker processes (default: one per core)")
    lab.add_argument(
        "--cluster", type=_cluster, help="address of a running Dask scheduler, e.g. tcp://host:8786"
    )
    lab.set_defaults(func=_cmd_lights)

    plt = command(
        "plot",
        "plot a sweep's results (PNG): moves vs k·D, failure rates, events per move; or a lights table's "
        "matrix of merges",
    )
    plt.add_argument("results", type=Path, help="the results file of apf-viz sweep or apf-viz lights")
    plt.add_argument("--out", type=Path, default=Path("plots"), help="folder for the PNGs")
    plt.set_defaults(func=_cmd_plot)

    sch = command("schedule", "write the schedule (who acted and the flips, not what they saw) of a trace")
    sch.add_argument("--from-trace", required=True, type=Path, help="the trace file (JSON Lines)")
    sch.add_argument("--out", type=Path, help="write to this file (atomically) instead of standard output")
    sch.add_argument(
        "--robots-out", type=Path, help="also write the trace's start (with its flips) as a robots file"
    )
    sch.add_argument("--pattern-out", type=Path, help="also write the trace's pattern as a pattern file")
    sch.set_defaults(func=_cmd_schedule)

    rep = command("replay", "re-run a trace file exactly and check every event")
    rep.add_argument("--trace", required=True, type=Path, help="the trace file (JSON Lines)")
    rep.add_argument(
        "--algorithm",
        help="replay with this algorithm instead of the one the trace names (the only way to replay a "
        "trace of your own module:Name algorithm: a file never loads code)",
    )
    rep.add_argument("--json", action="store_true", help="print the outcome as one JSON object")
    rep.set_defaults(func=_cmd_replay)

    rnd = command("random-robots", "print a random solvable start as a robots file")
    _add_box_options(rnd, "robots")
    rnd.add_argument("--allow-unsolvable", action="store_true", help="do not redraw symmetric starts")
    rnd.set_defaults(func=_cmd_random_robots)

    rpat = command("random-pattern", "print a random pattern as a pattern file")
    _add_box_options(rpat, "pattern points")
    rpat.add_argument("--name", help="the pattern's name in the file")
    rpat.set_defaults(func=_cmd_random_pattern)

    _add_pattern_options(
        command("pattern", "make a pattern (or robots) file from text, ASCII art or a shape")
    )

    chk = command("check", "explore every schedule of a small start (model checking)")
    chk.add_argument("--robots", required=True, type=Path, help="start file (keep k ≤ 5)")
    chk.add_argument("--pattern", required=True, type=Path, help="pattern file with one point per robot")
    chk.add_argument(
        "--scheduler", default="async", choices=["async", "ssync", "fsync"], help="the adversary explored"
    )
    chk.add_argument(
        "--flips",
        default="file",
        choices=["all", "file"],
        help="every assignment of y-axis flips, or the file's (a file without y_up: random from --seed)",
    )
    chk.add_argument(
        "--seed", type=int, default=1, help="seed of the y-axis flips when the robots file gives none"
    )
    chk.add_argument(
        "--max-states", type=_positive, default=1_000_000, help="stop with verdict 'budget' beyond this"
    )
    chk.add_argument("--algorithm", default=DEFAULT_ALGORITHM, help=ALGORITHM_HELP)
    chk.add_argument(
        "--light-semantics", default="compute", choices=["compute", "lc-atomic"], help=SEMANTICS_HELP
    )
    chk.add_argument(
        "--no-reduction",
        action="store_true",
        help="explore every interleaving (without it, ASYNC skips the orders of invisible events: the same "
        "verdict and counterexample, fewer states; docs/VERIFICATION.md)",
    )
    chk.add_argument("--json", action="store_true", help="print the verdict as one JSON object")
    chk.add_argument("--force", action="store_true", help="explore an unsolvable start anyway")
    chk.add_argument("--counterexample", type=Path, help="write a failing schedule here as a trace file")
    chk.set_defaults(func=_cmd_check)

    lec = command("lecture", "check a guided lecture: run every stop headless, report each condition")
    lec.add_argument("action", choices=["check"], help="what to do with the lecture")
    lec.add_argument(
        "file", type=Path, help="a lecture file (JSON), or a shipped lecture's name: algorithm-in-12-stops, …"
    )
    lec.set_defaults(func=_cmd_lecture)

    serve = command("serve", "serve the visualiser (the default command)")
    _add_serve_options(serve)
    serve.set_defaults(func=_cmd_serve)
    return parser


def _add_serve_options(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--host",
        default="127.0.0.1",
        help="address to bind; anyone who can reach it can drive the run and upload files (README, "
        "'Who can reach the server')",
    )
    p.add_argument("--port", type=_port, default=8080, help="port")
    p.add_argument("--robots", type=Path, help="start file (default: the built-in demo)")
    p.add_argument("--pattern", type=Path, help="pattern file (default: the built-in demo)")
    p.add_argument("--trace", type=Path, help="open this trace, to step through it")
    p.add_argument(
        "--lecture",
        help="open this guided lecture (a file, or a shipped lecture's name) at its first stop, presenting",
    )
    p.add_argument(
        "--library",
        type=Path,
        help="the folder of saved patterns (Edit: Save pattern, Saved; default: the user's data directory)",
    )
    _add_run_options(p, list(SCHEDULERS))


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    if not argv or (argv[0].startswith("-") and argv[0] not in ("-h", "--help")):
        argv = ["serve", *argv]  # the visualiser is the default command
    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except WalkMismatch as e:
        _fail(str(e), EXIT_WALK_MISMATCH)
    except InputError as e:
        _fail(str(e))
    except ValueError as e:
        _fail(str(e))
    except OSError as e:
        _fail(f"{e.filename or ''}: {e.strerror}".lstrip(": "))


if __name__ == "__main__":
    sys.exit(main())
