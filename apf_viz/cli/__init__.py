"""The ``apf-viz`` command line: a module per command (its ``NAME``, ``HELP``, ``add_arguments`` and
``run``), listed once in :data:`COMMANDS`.

Exit codes: 0 formed (or success), 1 ran but not formed, 2 bad input, 3 unsolvable start (Theorem 1),
4 check's state budget exhausted, 5 a fast-forward walk that is not the step-by-step run. Every error
is one line on stderr, never a traceback.
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
from collections.abc import Sequence
from pathlib import Path
from types import ModuleType

from apf_viz import interrupted_while_starting
from apf_viz.cli import (
    adversary,
    check,
    demos,
    docs,
    export,
    figure,
    hunt,
    lecture,
    lights,
    pattern,
    plot,
    random_pattern,
    random_robots,
    replay,
    run,
    schedule,
    serve,
    sweep,
)
from apf_viz.cli.common import (
    EXIT_BAD_INPUT,
    EXIT_FORMED,
    EXIT_NOT_FORMED,
    EXIT_UNSOLVABLE,
    EXIT_WALK_MISMATCH,
    HelpFormatter,
    Parser,
    fail,
)
from apf_viz.core.fast_forward import WalkMismatch
from apf_viz.core.files import InputError, inputs_guarded, refuse_input_as_output

COMMANDS: tuple[ModuleType, ...] = (
    run,
    sweep,
    lights,
    plot,
    schedule,
    replay,
    random_robots,
    random_pattern,
    pattern,
    check,
    hunt,
    adversary,
    lecture,
    figure,
    export,
    demos,
    docs,
    serve,
)
"""Every command, in the order ``--help`` lists them; ``serve`` is the default."""

__all__ = [
    "COMMANDS",
    "EXIT_BAD_INPUT",
    "EXIT_FORMED",
    "EXIT_NOT_FORMED",
    "EXIT_UNSOLVABLE",
    "EXIT_WALK_MISMATCH",
    "build_parser",
    "main",
]


def build_parser() -> Parser:
    parser = Parser(
        prog="apf-viz",
        formatter_class=HelpFormatter,
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
    sub = parser.add_subparsers(dest="command", parser_class=Parser)
    for command in COMMANDS:
        p = sub.add_parser(
            command.NAME, help=command.HELP, description=command.HELP, formatter_class=HelpFormatter
        )
        command.add_arguments(p)
        parser.commands[command.NAME] = p
        p.set_defaults(func=command.run, _outputs=getattr(command, "OUTPUTS", ()))
    return parser


def _option(name: str) -> str:
    return f"--{name.replace('_', '-')}"


def refuse_inputs_as_outputs(args: argparse.Namespace) -> None:
    """Before any work: no output option names a file that another option names (an input, or another
    output), whether by the same path, a symbolic link or a hard link."""
    outputs = {_option(n): v for n in args._outputs if (v := getattr(args, n, None)) is not None}
    others = {
        _option(n) if n != "results" else n: v
        for n, v in vars(args).items()
        if isinstance(v, Path) and _option(n) not in outputs
    }
    seen: dict[str, Path] = {}
    for option, path in outputs.items():
        refuse_input_as_output(path, {**others, **seen})
        seen[option] = path


def main(argv: Sequence[str] | None = None) -> int:
    if signal.getsignal(signal.SIGINT) is interrupted_while_starting:
        signal.signal(signal.SIGINT, signal.default_int_handler)  # started: a command handles its Ctrl+C
    argv = list(sys.argv[1:] if argv is None else argv)
    if not argv or (argv[0].startswith("-") and argv[0] not in ("-h", "--help")):
        argv = ["serve", *argv]  # the visualiser is the default command
    parser = build_parser()
    args, unknown = parser.parse_known_args(argv)
    if unknown:  # said by the command's own parser: "apf-viz run: error: …", and its --help
        parser.commands[args.command].error(f"unrecognized arguments: {' '.join(unknown)}")
    try:
        if args.command == "serve":  # the visualiser's saves are the user's own choice of file
            return args.func(args)
        refuse_inputs_as_outputs(args)
        with inputs_guarded():
            return args.func(args)
    except KeyboardInterrupt:  # before a command's own handling (an import, a file being read)
        print("apf-viz: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:  # a listing piped into head: the reader has what it wanted
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())  # Python would fail again flushing stdout at exit
        os.close(devnull)
        return 0
    except WalkMismatch as e:
        fail(str(e), EXIT_WALK_MISMATCH)
    except InputError as e:
        fail(str(e))
    except ValueError as e:
        fail(str(e))
    except OSError as e:
        fail(f"{e.filename or ''}: {e.strerror}".lstrip(": "))
