"""A long job's progress line on the terminal, which never stops the job.

A sweep or a lab prints its progress to stderr as it goes. If whoever reads that stream goes away (the
terminal closed, or a pipe into a command that stopped reading: ``apf-viz sweep … 2>&1 | head``), the next
write fails with ``BrokenPipeError``; the job must go on and keep its results, so the line is dropped and
stderr pointed at the null device from then on (Python would otherwise fail again flushing it at exit).
"""

from __future__ import annotations

import os
import sys


def show_progress(line: str, *, last: bool) -> None:
    """Overwrite the terminal's current line with ``line`` (ending it if ``last``)."""
    try:
        print(f"\r{line}\x1b[K", end="\n" if last else "", file=sys.stderr, flush=True)
    except BrokenPipeError:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stderr.fileno())
        os.close(devnull)
