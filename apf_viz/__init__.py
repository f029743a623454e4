"""apf-viz: an interactive workbench for asynchronous opaque luminous robots on the infinite grid."""

# contextlib, os and sys are loaded by Python's own start: before the handler below, only signal is new
# (typing, which takes a while, is imported after it).
import contextlib
import os
import signal
import sys

__version__ = "0.1.0"
__all__ = [
    "Found",
    "LectureChecked",
    "Run",
    "Shown",
    "Verdict",
    "Worst",
    "__version__",
    "adversary",
    "check",
    "hunt",
    "lecture_check",
    "plot",
    "run",
    "sweep",
]


def __getattr__(name: str) -> object:
    """The library (apf_viz.api) is loaded when first asked for: ``apf-viz …`` starts without it."""
    if name in __all__:
        import apf_viz.api

        return getattr(apf_viz.api, name)
    raise AttributeError(f"module 'apf_viz' has no attribute {name!r}")


def __dir__() -> list[str]:
    """What tab completion and ``dir(apf_viz)`` offer: the library, not the modules this file uses."""
    return sorted(__all__)


def interrupted_while_starting(signum: int, frame: object) -> None:
    """Ctrl+C while the command line imports what it needs (seconds on a busy machine): one line."""
    sys.stderr.write("apf-viz: interrupted\n")
    sys.stderr.flush()
    os._exit(130)


# Only the command line starting (`apf-viz …`, or `python -m apf_viz.cli`, whose package is imported while
# sys.argv[0] is still "-m"), never a notebook importing the library; `cli.main` restores Python's own
# handler, so that a command's Ctrl+C keeps what it has done.
_STARTING = sys.argv[:1] == ["-m"] or os.path.basename(sys.argv[0] if sys.argv else "") == "apf-viz"
if _STARTING:
    with contextlib.suppress(ValueError):  # imported from a thread other than the main one: nothing to do
        signal.signal(signal.SIGINT, interrupted_while_starting)

from typing import TYPE_CHECKING  # noqa: E402  (after the handler: a Ctrl+C during it is one line)

if TYPE_CHECKING:
    from apf_viz.api import (
        Found,
        LectureChecked,
        Run,
        Shown,
        Verdict,
        Worst,
        adversary,
        check,
        hunt,
        lecture_check,
        plot,
        run,
        sweep,
    )
