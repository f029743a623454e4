"""The presenter code: where viser does not say which address a page was opened at (ui/viser_compat.py),
every page opens as a class page, and a presenter takes control by typing the code the terminal printed
into this field. Shown only then, and only on a class page; a few wrong codes and the field is closed."""

from __future__ import annotations

from collections.abc import Callable

from apf_viz.ui.panels.context import PanelContext
from apf_viz.workbench.view_model import SessionView

CODE_LENGTH = 10  # workbench/classroom/roles.py's presenter code: 10 hex digits
Claim = Callable[[str], str]  # a code typed → what to tell the page (the App checks it)


class PresenterCode:
    def __init__(self, gui, ctx: PanelContext, claim: Claim | None) -> None:
        self.ctx, self.claim = ctx, claim
        self.field = gui.add_text(
            "Presenter code",
            initial_value="",
            hint="the code the terminal printed: this page then presents (drives the shared run)",
            visible=False,
            order=-1.0,  # first in the panel: where the person looks who was told to type it
        )
        self.field.on_update(ctx.guard(self._typed, "Presenter code", mine=True))

    def _typed(self, event) -> str | None:
        code = self.field.value.strip()
        if event.client is None or not code or self.claim is None or len(code) < CODE_LENGTH:
            return None  # each key typed is reported: a code is checked once it is whole
        self.field.value = ""
        return self.claim(code)

    def refresh(self, view: SessionView) -> None:
        shown = self.claim is not None and self.ctx.classroom.role(self.ctx.browser) == "class"
        if self.field.visible != shown:
            self.field.visible = shown
