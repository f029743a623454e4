"""The run a page is attached to: the shared session, or a run of its own (ui/own_runs.py)."""

from __future__ import annotations

from apf_viz.workbench.session import Session


class Attachment:
    """The run a page is attached to: the shared session, or its own (``own``). It stands for that
    session wherever the page's panel holds one, so the panel's commands always reach the right run."""

    def __init__(self, shared: Session) -> None:
        self.shared = shared
        self.own: Session | None = None

    @property
    def target(self) -> Session:
        return self.own if self.own is not None else self.shared

    def __getattr__(self, name: str):
        # Only names not found on the Attachment itself come here: every Session attribute and command.
        return getattr(self.target, name)
