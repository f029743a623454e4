"""What the commands share: exit codes, one-line errors, argument types and the option groups several
commands take."""

from __future__ import annotations

import argparse
import json
import re
import signal
import sys
from collections.abc import Sequence
from dataclasses import asdict
from pathlib import Path
from typing import NoReturn

from apf_viz.algorithms import ALGORITHMS, DEFAULT_ALGORITHM, algorithm_from_command_line
from apf_viz.core.files import check_writable, write_atomic
from apf_viz.core.formats import check_sizes, load_pattern, load_robots
from apf_viz.core.grid import as_point
from apf_viz.core.run import RunSummary
from apf_viz.core.schedulers import DEFAULT_SCHEDULER, REGISTRY
from apf_viz.core.symmetry import unsolvable_start
from apf_viz.demos import shipped_file

EXIT_FORMED, EXIT_NOT_FORMED, EXIT_BAD_INPUT, EXIT_UNSOLVABLE = 0, 1, 2, 3
EXIT_WALK_MISMATCH = 5  # --check-walks found a walk that is not the step-by-step run


class Parser(argparse.ArgumentParser):
    """One-line errors (exit 2), and no abbreviations: ``--robot`` is a typo, not ``--robots``."""

    def __init__(self, *args, **kwargs) -> None:
        kwargs.setdefault("allow_abbrev", False)
        super().__init__(*args, **kwargs)
        self.commands: dict[str, Parser] = {}  # the top-level parser's: each command's own parser

    def error(self, message: str) -> NoReturn:
        self.exit(EXIT_BAD_INPUT, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def fail(message: str, code: int = EXIT_BAD_INPUT) -> NoReturn:
    print(f"apf-viz: error: {message}", file=sys.stderr)
    raise SystemExit(code)


def stop_on_sigterm_as_on_ctrl_c() -> None:
    """SIGTERM (a batch system's stop, a `kill`) raises KeyboardInterrupt as Ctrl+C does, so that a long
    command keeps what it has done: Python's own handler, not SIGINT's current one, which a background
    job may have ignored."""
    signal.signal(signal.SIGTERM, signal.default_int_handler)


def int_within(low: int, high: float, what: str):
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


positive = int_within(1, float("inf"), "a positive integer")
# Seeds are 0 or more everywhere: --seed, sweep's --seeds, and apf_viz.run / check / sweep.
seed = int_within(0, float("inf"), "a seed (an integer, 0 or more)")


# A local worker is a process of its own (about 100 MB with its imports): more than this per core only
# queue behind each other, and 100,000 of them would never start.
WORKERS_PER_CORE = 4
CLUSTER = re.compile(r"((tcp|tls|ws|wss|ucx)://)?(\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9.-]+):[0-9]{1,5}")


def workers(text: str) -> int:
    """An argparse type: local worker processes, at most ``WORKERS_PER_CORE`` per core of this machine."""
    from apf_viz.sweeps import usable_cores

    n = positive(text)
    most = WORKERS_PER_CORE * usable_cores()
    if n > most:
        raise argparse.ArgumentTypeError(
            f"{n:,} local worker processes: this machine can run at most {most} ({WORKERS_PER_CORE} per "
            "core); for more, start a Dask cluster and give --cluster"
        )
    return n


def cluster(text: str) -> str:
    """An argparse type: a Dask scheduler's network address (``tcp://HOST:PORT``; an in-process
    address names nothing another process can reach)."""
    if not CLUSTER.fullmatch(text):
        raise argparse.ArgumentTypeError(
            f"{text!r} is not a Dask scheduler's address: give tcp://HOST:PORT (or tls://, ws://, wss://)"
        )
    return text


def positive_seconds(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number of seconds") from None
    if not 0 < value < float("inf"):
        raise argparse.ArgumentTypeError(f"{text} is not a positive number of seconds")
    return value


port = int_within(0, 65535, "a port (0 to 65535)")


def shipped(path: Path | None, kind: str, option: str) -> Path | None:
    """``path``, or when no such file exists, the packaged demo file its name stands for (said on
    stderr: which file was used); a file of that name always wins."""
    if path is None or path.exists():
        return path
    found = shipped_file(str(path), kind)
    if found is None:
        return path  # the load says: no such file
    print(f"apf-viz: {option} {path}: the shipped {kind} file {found}", file=sys.stderr)
    return found


def refuse_unsolvable(robots_path: Path, points: list, targets: list, as_json: bool) -> None:
    """Theorem 1: a start mirror-symmetric about a robot-free horizontal line cannot form any pattern
    (unless it already is the pattern). Exit 3, naming the axis."""
    refused = unsolvable_start(points, targets)
    if refused is None:
        return
    axis, why = refused
    message = f"{robots_path}: {why}; --force runs it anyway"
    if as_json:
        print(json.dumps({"outcome": "unsolvable", "axis": float(axis), "message": message}))
    fail(message, EXIT_UNSOLVABLE)


def problem(args: argparse.Namespace, output: Path | None):
    """What ``run`` and ``check`` start from: the robots file, its points, the pattern's points and the
    algorithm, every input checked (and the output path, before any work) with one-line errors."""
    args.robots = shipped(args.robots, "robots", "--robots")
    args.pattern = shipped(args.pattern, "pattern", "--pattern")
    robots = load_robots(args.robots)
    pattern = load_pattern(args.pattern)
    check_sizes(robots, pattern, str(args.pattern))
    algorithm, _ = algorithm_from_command_line(args.algorithm)
    if output:
        check_writable(output)  # before the work, not after minutes of it
    points = [as_point(p) for p in robots.robots]
    targets = [as_point(p) for p in pattern.points]
    if not args.force:
        refuse_unsolvable(args.robots, points, targets, args.json)
    return robots, points, targets, algorithm


def _listed(names: Sequence[str]) -> str:
    """``a``, ``a and b``, ``a, b and c``."""
    return names[0] if len(names) == 1 else f"{', '.join(names[:-1])} and {names[-1]}"


def need_extra(command: str, modules: Sequence[str]) -> None:
    """Refuse in one line, before any work, a command whose optional packages are not installed."""
    import importlib.util

    missing = [m for m in modules if importlib.util.find_spec(m) is None]
    if missing:
        fail(
            f"apf-viz {command} needs the sweep extra ({_listed(missing)} "
            f"{'is' if len(missing) == 1 else 'are'} not installed): "
            "pip install 'apf-viz[sweep]' (or, in a checkout, pip install -e '.[sweep]')"
        )


def print_summary(summary: RunSummary, as_json: bool) -> None:
    if as_json:
        data = asdict(summary)
        data["final"] = [list(p) for p in summary.final]
        print(json.dumps(data))
    else:
        limit = ""
        if summary.outcome == "limit":
            held = f" or {summary.max_recorded:,} steps held in memory" if summary.max_recorded else ""
            limit = f" (the run's cap: {summary.max_moves:,} moves, {summary.max_events:,} events{held})"
        print(
            f"{summary.outcome}{limit}: {summary.events} events, {summary.moves} moves "
            f"(moves/(k·D) = {summary.moves_per_kD:.3f}), {summary.cycles} cycles, {summary.skipped} "
            f"robot·steps passed over; lights used: {', '.join(summary.lights_used)}"
        )


def emit(text: str, out: Path | None) -> None:
    if out:
        write_atomic(out, text)
    else:
        sys.stdout.write(text)


class HelpFormatter(argparse.HelpFormatter):
    """Every option's help ends with its default, when it has one worth showing."""

    def _get_help_string(self, action: argparse.Action) -> str:
        text = action.help or ""
        default = action.default
        if "%(default)" in text or default in (None, False, argparse.SUPPRESS) or not action.option_strings:
            return text
        return f"{text} (default: %(default)s)"


ALGORITHM_HELP = (
    f"the algorithm: {', '.join(ALGORITHMS)}; apf-opaque-grid@R1,R2 for exactly these resolutions "
    "(apf-viz docs algorithm); or package.module:Name for your own"
)
SEMANTICS_HELP = "when a new light becomes visible: at the end of Compute, or Look+Compute atomic"


def add_run_options(p: argparse.ArgumentParser, schedulers: Sequence[str], defaults: bool = True) -> None:
    """The adversary's options. ``defaults=False`` (``run``) leaves --scheduler and --light-semantics
    None when not given, so that a --schedule can tell them apart from the defaults."""
    p.add_argument(
        "--scheduler",
        default=DEFAULT_SCHEDULER if defaults else None,
        choices=list(schedulers),
        help="the adversary: "
        + "; ".join(f"{kind.name}, {kind.summary}" for kind in REGISTRY if kind.name in schedulers)
        + ("" if defaults else f" (default: {DEFAULT_SCHEDULER})"),
    )
    p.add_argument(
        "--seed",
        type=seed,
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


def add_box_options(p: argparse.ArgumentParser, what: str) -> None:
    p.add_argument("--count", type=int, required=True, help=f"number of {what}")
    p.add_argument("--width", type=int, required=True, help="the box is x = 0 .. width-1")
    p.add_argument("--height", type=int, required=True, help="the box is y = 0 .. height-1")
    p.add_argument("--seed", type=seed, default=1, help="the same seed draws the same points")
    p.add_argument("--out", type=Path, help="write to this file (atomically) instead of standard output")
