"""Why: the selected robot's last decision, its rule and the predicates it tested."""

from __future__ import annotations

from apf_viz.ui.panels.context import PanelContext, put
from apf_viz.workbench.view_model import SessionView
from apf_viz.workbench.view_model.why import why_markdown


class WhyFolder:
    def __init__(self, gui, ctx: PanelContext) -> None:
        with gui.add_folder("Why"):
            self.markdown = gui.add_markdown(why_markdown(None))

    def refresh(self, view: SessionView) -> None:
        put(self.markdown, content=view.why_text)
