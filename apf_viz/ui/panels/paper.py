"""Paper: the algorithm's pseudocode as its paper writes it, the line of the selected robot's last
decision (or the run's last Compute) highlighted and the conditions it sits in marked; a resolution's
line in its own colour, named, with its reason (ui/presenter/paper.py)."""

from __future__ import annotations

from apf_viz.ui.panels.context import PanelContext
from apf_viz.ui.presenter import SessionView


class PaperFolder:
    def __init__(self, gui, ctx: PanelContext) -> None:
        with gui.add_folder("Paper"):
            self.html = gui.add_html("")

    def refresh(self, view: SessionView) -> None:
        if self.html.content != view.paper_text:
            self.html.content = view.paper_text
