"""A long job's progress line on the terminal, which never stops the job.

A sweep or a lab prints its progress to stderr as it goes. If whoever reads that stream goes away (the
terminal closed, or a pipe into a command that stopped reading: ``apf-viz sweep … 2>&1 | head``), the next
write fails with ``BrokenPipeError``; the job must go on and keep its results, so the line is dropped and
stderr pointed at the null device from then on (Python would otherwise fail again flushing it at exit).
"""

from __future__ import annotations

import os
import sys
import time

PLAIN_EVERY_S = 1.0
"""Into a file or a pipe (a log), a progress line at most this often (a second: a test or a script
waiting on a word sees it soon), and the last: no terminal codes."""

_plain_at = [-PLAIN_EVERY_S]  # when the last plain line was written (monotonic seconds)


def show_progress(line: str, *, last: bool) -> None:
    """Overwrite the terminal's current line with ``line`` (ending it if ``last``); into a file or a
    pipe, write it as a line of its own every :data:`PLAIN_EVERY_S` seconds, and the last one."""
    try:
        if not sys.stderr.isatty():
            now = time.monotonic()
            if last or now - _plain_at[0] >= PLAIN_EVERY_S:
                _plain_at[0] = now
                print(line, file=sys.stderr, flush=True)
            return
        print(f"\r{line}\x1b[K", end="\n" if last else "", file=sys.stderr, flush=True)
    except BrokenPipeError:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stderr.fileno())
        os.close(devnull)
