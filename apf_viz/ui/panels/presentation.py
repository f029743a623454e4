"""Presentation mode (P, or the Run folder's button): this browser's panel collapses and a large caption
floats over the canvas — the stage, the last event, a failure's outcome, the lights in use — while the
keyboard drives the run (ui/panels/shortcuts.py). Another browser's screen is not touched."""

from __future__ import annotations

from apf_viz.ui.panels.context import PanelContext
from apf_viz.ui.presenter import SessionView
from apf_viz.ui.presenter.legend import lecture_html
from apf_viz.ui.recorder import canvas_size

# The caption floats over the top of the canvas, this share of its height; a framed camera leaves that
# room free (ui/app.py), so the caption never covers the run.
PRESENTATION_TOP_ROOM = 0.35


class Presentation:
    def __init__(self, gui, ctx: PanelContext) -> None:
        self.gui, self.ctx = gui, ctx
        self.panel = None
        self.html = None
        command = gui.add_command(
            "Presentation mode", description="collapse the panel; a large caption on the canvas", hotkey="P"
        )
        command.on_trigger(ctx.guard(self.toggle))
        ctx.toggle_presentation = self.toggle
        ctx.presenting = lambda: self.on

    @property
    def on(self) -> bool:
        return self.panel is not None

    def toggle(self, event=None) -> None:
        if self.panel is None:
            self.gui.main_panel.minimize()
            self.panel = self.gui.add_panel()
            with self.panel.add_tab("Caption"):
                self.html = self.gui.add_html("")
            height = canvas_size(event.client)[0] if event is not None and event.client is not None else 768
            self.panel.float(x=12, y=8, width=560, height=int(PRESENTATION_TOP_ROOM * height) - 12)
        else:
            self.panel.remove()
            self.panel = self.html = None
            self.gui.main_panel.expand()
        if event is not None and event.client is not None:
            self.ctx.frame(event.client)  # the caption's room at the top comes and goes
        self.ctx.changed()

    def refresh(self, view: SessionView) -> None:
        if self.html is not None:
            content = lecture_html(view)
            if self.html.content != content:
                self.html.content = content
