"""Compare: the same start, pattern and adversary under a second algorithm, drawn to the right."""

from __future__ import annotations

from apf_viz.ui.panels.context import PanelContext, put, tell
from apf_viz.workbench.view_model import SessionView


class CompareFolder:
    def __init__(self, gui, ctx: PanelContext) -> None:
        self.ctx = ctx
        with ctx.driving(gui.add_folder("Compare", expand_by_default=False)):
            self.compare_with = gui.add_text(
                "Compare with",
                initial_value="apf-opaque-grid-literal",
                hint="a second algorithm or variant (e.g. apf-opaque-grid@G1,G2): the same start, pattern "
                "and adversary, drawn to the right and stepping with the run",
            )
            gui.add_button_group("Compare runs", ("Compare", "Stop comparing")).on_click(self._on_compare)
            self.status = gui.add_markdown("")
            self.divergence = gui.add_button(
                "Go to divergence", visible=False, hint="the first event at which the two runs differ"
            )
            self.divergence.on_click(ctx.guard(self._to_divergence))

    def _to_divergence(self, event) -> None:
        at = self.ctx.view().divergence
        if at is not None:
            self.ctx.session.seek_event(at[0])

    def _on_compare(self, event) -> None:
        s = self.ctx.session
        if event.target.value == "Compare":
            name = self.compare_with.value.strip()
            if name == s.algorithm_name:
                tell(event.client, "Compare", f"the run already uses {name}: name another algorithm", True)
                return
            self.ctx.guard(lambda e: s.compare_with(name))(event)
        else:
            self.ctx.guard(lambda e: s.compare_with(None))(event)
        self.ctx.frame_all()  # both runs in view

    def refresh(self, view: SessionView) -> None:
        put(self.status, content=view.compare_text)
        if self.divergence.visible != (view.divergence is not None):
            self.divergence.visible = view.divergence is not None
