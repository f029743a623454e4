"""Paper: the algorithm's pseudocode as its paper writes it, the line of the selected robot's last
decision (or the run's last Compute) highlighted and the conditions it sits in marked; a resolution's
line in its own colour, named, with its reason (workbench/view_model/paper.py)."""

from __future__ import annotations

from apf_viz.lecture import figures
from apf_viz.ui.panels.context import PanelContext
from apf_viz.workbench.view_model import SessionView


class PaperFolder:
    def __init__(self, gui, ctx: PanelContext) -> None:
        self.ctx = ctx
        with gui.add_folder("Paper"):
            self.figure = ctx.driving(gui.add_dropdown(
                "Figure", ("—", *figures()), initial_value="—",
                hint="one of the paper's figures, reproduced: its scenario run to the event where the "
                "picture holds, the caption on screen",
            ))  # fmt: skip
            self.figure.on_update(ctx.from_browser(self._on_figure, "Figure"))
            self.html = gui.add_html("")

    def _on_figure(self, event) -> str | None:
        name = self.figure.value
        if name == "—":
            return None
        return self.ctx.session.start_lecture(figures()[name].as_lecture())

    def refresh(self, view: SessionView) -> None:
        if self.html.content != view.paper_text:
            self.html.content = view.paper_text
