"""Join from the wall: J (Ctrl+K: `Class address`) opens, on this page, the class address in large text
with its QR code (workbench/join.py), for a room to join from the projector; so does a lecture's stop
that asks for it (``"class_address": true``), on the presenter's page, until the lecture leaves it."""

from __future__ import annotations

from apf_viz.ui import viser_compat
from apf_viz.ui.panels.context import PanelContext
from apf_viz.workbench.join import join_html
from apf_viz.workbench.view_model import SessionView

JOIN_KEY = "J"


class Join:
    """The class address on this page, in a window of its own until closed (Escape or Close)."""

    def __init__(self, gui, ctx: PanelContext) -> None:
        self.gui, self.ctx = gui, ctx
        command = gui.add_command(
            "Class address",
            description="the address the class's laptops open, large, with its QR code",
            hotkey=JOIN_KEY,
        )
        command.on_trigger(lambda event: self.show())
        self._modal = None
        self._stop: tuple | None = None  # the lecture stop last seen: (lecture, index, event)
        self._by_stop = False  # the window was opened by a stop, and closes when the lecture moves on

    def show(self) -> None:
        """Open it (again: a window closed by its own × is opened anew)."""
        self.close()
        address = self.ctx.class_address()
        with self.gui.add_modal("Join this class") as modal:
            self.gui.add_html(
                viser_compat.WIDE_CLASS_ADDRESS
                + viser_compat.ESCAPE_CLOSES_CLASS_ADDRESS
                + join_html(address)
            )
            self.gui.add_button("Close").on_click(lambda event: self.close())
        self._modal = modal

    def close(self) -> None:
        if self._modal is not None:
            self._modal.close()
            self._modal = None
        self._by_stop = False

    def refresh(self, view: SessionView) -> None:
        """A lecture reaching a stop that asks for the class address shows it on the presenter's page;
        leaving that stop closes it."""
        session = self.ctx.session
        stop = session.screen.lecture
        key = (stop.lecture, stop.index, stop.event) if stop is not None else None
        if key == self._stop:
            return
        self._stop = key
        if stop is not None and stop.class_address and self.ctx.classroom.is_presenter(self.ctx.browser):
            self.show()
            self._by_stop = True
        elif self._by_stop:
            self.close()
