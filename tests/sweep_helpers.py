"""Helpers of the tests of long Dask commands (sweep, lights): a run function that kills its worker
process on one cell (a crash, not an exception; module level, so that Dask workers can import it), and
Ctrl+C pressed on a running command."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import time

from apf_viz.sweeps import Cell, run_cell


def crash_on_k4_seed2(cell: Cell, traces: str | None) -> dict:
    if cell.k == 4 and cell.seed == 2:
        os._exit(13)  # the worker dies mid-task
    return run_cell(cell, traces)


def interrupt_when(argv: list[str], cwd, progress: bytes) -> tuple[int, str]:
    """Run a command, press Ctrl+C as soon as its standard error matches the regex ``progress``, and
    return its exit code and all it wrote to standard error."""
    # A background job of a non-interactive shell ignores SIGINT, and a Python started so never raises
    # KeyboardInterrupt: the command gets the default handler back, as in a terminal.
    proc = subprocess.Popen(
        argv,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        cwd=cwd,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    seen, deadline = b"", time.time() + 120
    while time.time() < deadline and not re.search(progress, seen):
        chunk = proc.stderr.read1(4096)
        if not chunk:
            break
        seen += chunk
    proc.send_signal(signal.SIGINT)
    _, rest = proc.communicate(timeout=120)
    return proc.returncode, (seen + rest).decode()
