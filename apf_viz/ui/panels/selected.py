"""Selected robot: this browser's selection (its light, phase, flip, and what its snapshot holds), or the
presenter's when this browser follows it."""

from __future__ import annotations

from apf_viz.ui.panels.context import PanelContext, put
from apf_viz.workbench.view_model import SessionView


class SelectedFolder:
    def __init__(self, gui, ctx: PanelContext) -> None:
        self.ctx = ctx
        with gui.add_folder("Selected robot"):
            self.caption = gui.add_markdown("")
            self.follow = gui.add_checkbox(
                "Follow presenter",
                initial_value=False,
                hint="show the robot the presenter's browser selected (its rays, caption and Why) instead "
                "of your own; off, your clicks select for this browser only",
            )
            self.follow.on_update(
                ctx.from_browser(
                    lambda e: ctx.classroom.set_follow(ctx.browser, bool(self.follow.value)), mine=True
                )
            )

    def refresh(self, view: SessionView) -> None:
        presenting = self.ctx.classroom.is_presenter(self.ctx.browser)
        if self.follow.visible == presenting:
            self.follow.visible = not presenting  # the presenter follows nobody
        following = self.ctx.state.follow  # a click on a robot ends it
        if self.follow.value != following:
            self.follow.value = following
        head = "<small>Following the presenter's selection.</small>\n\n" if view.follows_presenter else ""
        put(self.caption, content=head + view.caption)
