"""apf-viz: an interactive workbench for asynchronous opaque luminous robots on the infinite grid."""

import os
import signal
import sys
import threading

__version__ = "0.1.0"


def interrupted_while_starting(signum: int, frame: object) -> None:
    """Ctrl+C while the command line imports what it needs (seconds on a busy machine): one line."""
    sys.stderr.write("apf-viz: interrupted\n")
    sys.stderr.flush()
    os._exit(130)


# Only the command line starting (`apf-viz …`, or `python -m apf_viz.cli`, whose package is imported while
# sys.argv[0] is still "-m"), never a notebook importing the library; `cli.main` restores Python's own
# handler, so that a command's Ctrl+C keeps what it has done.
_STARTING = sys.argv[:1] == ["-m"] or os.path.basename(sys.argv[0] if sys.argv else "") == "apf-viz"
if _STARTING and threading.current_thread() is threading.main_thread():
    signal.signal(signal.SIGINT, interrupted_while_starting)
