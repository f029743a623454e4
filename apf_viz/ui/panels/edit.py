"""Edit: draw the pattern or place the robots; switching back to Run checks the drafts and restarts."""

from __future__ import annotations

from apf_viz.ui.panels.context import PanelContext, tell
from apf_viz.ui.presenter import SessionView

MODES = {"Run": "run", "Edit pattern": "edit-pattern", "Edit robots": "edit-robots"}
MODE_LABELS = {v: k for k, v in MODES.items()}


class EditFolder:
    def __init__(self, gui, ctx: PanelContext) -> None:
        self.ctx = ctx
        with gui.add_folder("Edit", expand_by_default=False):
            self.mode = gui.add_dropdown("Mode", tuple(MODES), initial_value="Run")
            self.mode.on_update(self._on_mode)
            self.counts = gui.add_markdown("")
            gui.add_button("Clear pattern").on_click(ctx.guard(lambda e: ctx.session.clear_pattern()))

    def _on_mode(self, event) -> None:
        if event.client is None:
            return
        s = self.ctx.session
        mode = MODES.get(self.mode.value)
        problem = s.set_mode(mode) if mode is not None else f"no mode {self.mode.value!r}"  # type: ignore[arg-type]
        if problem:  # refused: the drafts stay, and the browser that asked is told why
            self.mode.value = MODE_LABELS[s.mode]
            tell(event.client, "Still editing", problem, error=True)
        self.ctx.changed()

    def refresh(self, view: SessionView) -> None:
        self.counts.content = view.counts
        if self.mode.value != MODE_LABELS[view.mode]:
            self.mode.value = MODE_LABELS[view.mode]
