"""Legend: every light of the algorithm with its meaning, its overlays, and every mark of the scene."""

from __future__ import annotations

from apf_viz.ui.panels.context import PanelContext
from apf_viz.workbench.view_model import SessionView
from apf_viz.workbench.view_model.legend import legend_html


class LegendFolder:
    def __init__(self, gui, ctx: PanelContext) -> None:
        with gui.add_folder("Legend"):
            self.html = gui.add_html("")

    def refresh(self, view: SessionView) -> None:
        legend = legend_html(view)  # its overlay rows change with the run (K appears, a frame is fixed)
        if self.html.content != legend:
            self.html.content = legend
