"""The library's progress: tqdm's bar (``tqdm.auto``: a widget in a notebook, a line in a terminal), the
one a notebook user knows, for every call that can take more than a few seconds; without tqdm (it comes
with the ``notebook`` extra), the command line's own progress line on stderr. ``progress=False`` on a
call shows nothing."""

from __future__ import annotations

import importlib.util
import time
from types import TracebackType
from typing import Any

from apf_viz.progress import show_progress

QUIET_FOR_S = 2.0
"""A call quicker than this shows no bar at all (most calls on small starts)."""


class ProgressBar:
    """One call's progress: :meth:`to` sets how far it is (``n`` of ``total``; a total of None: no
    ETA, only the count and its rate), with a short note after it; :meth:`close` ends it."""

    def __init__(self, what: str, total: int | None, unit: str, enabled: bool = True) -> None:
        self.what = what
        self.total = total
        self.unit = unit
        self.enabled = enabled
        self._bar: Any = None
        self._began = time.monotonic()
        self._shown = False  # the fallback line: written at least once
        if enabled and importlib.util.find_spec("tqdm") is not None:
            from tqdm.auto import tqdm  # type: ignore[import-untyped]

            self._bar = tqdm(
                total=total, desc=what, unit=f" {unit}", dynamic_ncols=True, leave=True, delay=QUIET_FOR_S
            )

    def to(self, n: int, note: str = "") -> None:
        """Move the bar to ``n``; nothing shows before the call has taken :data:`QUIET_FOR_S`.

        Args:
            n: how far the call is (of ``total``, when it has one).
            note: a few words after the count (e.g. ``frontier 1,234``); empty: none.
        """
        if not self.enabled:
            return
        if self._bar is None:
            if time.monotonic() - self._began < QUIET_FOR_S:
                return
            self._shown = True
            of = f"/{self.total:,}" if self.total is not None else ""
            show_progress(f"{self.what}: {n:,}{of} {self.unit}{'; ' + note if note else ''}", last=False)
            return
        if note:
            self._bar.set_postfix_str(note, refresh=False)
        self._bar.update(n - self._bar.n)  # update, not refresh: it keeps the quiet spell (delay)

    def close(self) -> None:
        """End the bar (without tqdm: a last ``done`` line, if the progress line was shown at all)."""
        if not self.enabled:
            return
        if self._bar is not None:
            self._bar.close()
        elif self._shown:
            show_progress(f"{self.what}: done", last=True)

    def __enter__(self) -> ProgressBar:
        return self

    def __exit__(
        self, kind: type[BaseException] | None, error: BaseException | None, tb: TracebackType | None
    ) -> None:
        self.close()
