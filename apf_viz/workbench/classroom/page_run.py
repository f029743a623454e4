"""A page's door to the run it drives: the shared run, or its own. A page's panel holds a
:class:`PageRun` wherever it would hold a Session, so every command it sends (Step, Back, Play, the
scheduler, a click, Why) goes to the run the page is attached to now, and nothing of a page's own run
reaches the shared one. What only the shared run may do is refused at this door while the page runs its
own: uploads, lectures, the pattern library on the server's disk, a stop's reveal. Refused here, not in
a control, so that no control or key can reach them from a run of one's own."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from apf_viz.core.formats import InputError
from apf_viz.workbench.classroom.pages import Page
from apf_viz.workbench.session import Session

__all__ = ["SHARED_ONLY", "PageRun"]

SHARED_ONLY = frozenset(
    {
        "load_pattern",
        "load_robots",
        "load_trace",
        "load_schedule",
        "start_lecture",
        "load_lecture",
        "seat_the_room",
        "reveal",
        "use_library",
        "save_pattern",
    }
)
"""The Session commands a page may send only to the shared run (tests/test_classroom.py tries each)."""


class PageRun:
    """The run ``page`` is attached to: its own, if it tries one, else ``shared``. Reads and commands
    pass through to that Session; a :data:`SHARED_ONLY` command is refused in a run of one's own."""

    def __init__(self, shared: Session, page: Page) -> None:
        self._shared = shared
        self._page = page

    @property
    def target(self) -> Session:
        """The Session the page drives now: its own run, or the shared one."""
        own = self._page.own
        return own if own is not None else self._shared

    @property
    def own(self) -> bool:
        """Whether the page drives a run of its own now."""
        return self._page.own is not None

    def __getattr__(self, name: str) -> Any:
        # Only names not found on the door itself come here: every Session attribute and command.
        value = getattr(self.target, name)
        if name in SHARED_ONLY and self._page.own is not None:
            return _refused(name)
        return value


def _refused(name: str) -> Callable[..., Any]:
    def refuse(*args: object, **kwargs: object) -> Any:
        raise InputError(f"{name.replace('_', ' ')}: not in a run of your own (Back to the lecture first)")

    return refuse
