"""Local worker processes for :func:`~apf_viz.api.sweeps.sweep` and :func:`~apf_viz.api.hunts.hunt`.

Dask starts its local workers with multiprocessing's *spawn*: each worker imports the script that called
the library (as ``__mp_main__``) before it runs anything. A script without ``if __name__ ==
"__main__":`` calls the library again while that worker starts, and a script read from standard input
cannot be imported at all; either way Dask reports "Nanny failed to start" under pages of tracebacks.
This module says it in one line instead, before any worker starts (and, in a worker, leaves quietly)."""

from __future__ import annotations

import contextlib
import inspect
import os
import sys
from collections.abc import Iterator

from apf_viz.core.formats import InputError


def refuse_unstartable_workers(call: str) -> None:
    """Refuse, in one line, a call whose local workers could not start (see the module's words)."""
    if _called_from_a_worker_import():
        # A worker being started imports the caller's script, which calls us again: leave without a
        # traceback (SystemExit prints none); the caller then gets unguarded()'s line from Dask's failure.
        raise SystemExit(1)
    main = sys.modules.get("__main__")
    path = getattr(main, "__file__", None)
    if path is not None and not os.path.isfile(path):
        raise InputError(
            f"{call} starts worker processes, which import the script that calls it: {path} is not a file "
            "they can import (standard input?); save the script as a file, or give cluster="
        )


def unguarded(call: str) -> InputError:
    """What Dask's "Nanny failed to start" means when the caller is a script: said in one line."""
    script = getattr(sys.modules.get("__main__"), "__file__", None) or "the calling script"
    return InputError(
        f"{call}'s worker processes could not start: each imports {script}, so call {call} under "
        'if __name__ == "__main__": (docs/API.md)'
    )


def _called_from_a_worker_import() -> bool:
    """Some caller is the script being imported by a worker that starts (run as ``__mp_main__``)."""
    frame = inspect.currentframe()
    while frame is not None:
        if frame.f_globals.get("__name__") == "__mp_main__":
            return True
        frame = frame.f_back
    return False


@contextlib.contextmanager
def local_workers(call: str, cluster: str | None) -> Iterator[None]:
    """Around a call that starts local workers (none with ``cluster``): refused first where they could
    not start, and Dask's "Nanny failed to start" said as :func:`unguarded`'s one line."""
    if cluster is not None:
        yield
        return
    refuse_unstartable_workers(call)
    try:
        yield
    except RuntimeError as e:
        if "failed to start" in str(e):
            raise unguarded(call) from None
        raise
