"""The Room folder, on the presenter's page only (workbench/classroom/room_list.py): every class page in
a line (anonymous: "laptop 7"), which follow the lecture and which try a run of their own (how far, what
outcome, whether it answered the stop's question); a laptop's run put beside the shared run on the
projector and taken down; the shared run handed to one laptop and taken back."""

from __future__ import annotations

import threading
import time

from apf_viz.core.formats import InputError
from apf_viz.ui.panels.context import PanelContext, put
from apf_viz.workbench.view_model import SessionView

NOBODY = "—"
# The list is redrawn at most this often: a class's own runs change it every frame they play, and the
# presenter's page would lay out a long list again each time (its updates of the run come first).
LIST_EVERY_S = 1.0


class RoomFolder:
    def __init__(self, gui, ctx: PanelContext) -> None:
        self.ctx = ctx
        self._listed = -LIST_EVERY_S  # when the list was last made (monotonic s)
        self._pending = False  # a frame is asked for when the list may be made again
        self.folder = gui.add_folder("Room", expand_by_default=False, visible=False)
        with self.folder:
            self.list = gui.add_markdown("")
            self.laptop = gui.add_dropdown("Laptop", (NOBODY,), initial_value=NOBODY)
            self.show = gui.add_button(
                "Show its run beside", hint="its own run on the projector, right of the lecture's"
            )
            self.take_down = gui.add_button("Take it down")
            self.hand = gui.add_button("Hand it the run", hint="this laptop may drive the lecture's run too")
            self.take_back = gui.add_button("Take the run back")
        self.show.on_click(ctx.guard(lambda e: self._room().show(self._chosen()), "Room"))
        self.take_down.on_click(ctx.guard(lambda e: self._room().show(None), "Room"))
        self.hand.on_click(ctx.guard(lambda e: self._room().hand(self._chosen(), ctx.browser), "Room"))
        self.take_back.on_click(ctx.guard(lambda e: self._room().hand(None, ctx.browser), "Room"))

    def _room(self):
        if not self.ctx.classroom.is_presenter(self.ctx.browser):
            raise InputError("the Room is the presenter's")
        return self.ctx.classroom

    def _chosen(self) -> int:
        value = self.laptop.value
        if value == NOBODY:
            raise InputError("choose a laptop first")
        return int(value.split()[-1])

    def _due(self) -> None:
        self._pending = False
        self.ctx.changed()

    def refresh(self, view: SessionView) -> None:
        room = self.ctx.classroom
        mine = room.is_presenter(self.ctx.browser) and not self.ctx.in_own_run()
        put(self.folder, visible=mine)
        if not mine:
            return
        now = time.monotonic()
        if now - self._listed < LIST_EVERY_S:
            if not self._pending:  # a frame when the wait is over, if none comes meanwhile
                self._pending = True
                timer = threading.Timer(LIST_EVERY_S - (now - self._listed), self._due)
                timer.daemon = True
                timer.start()
            return
        self._listed = now
        pages = room.listing()
        lines = [f"- {page.words()}" for page in pages]
        own = sum(page.own for page in pages)
        head = (
            f"**{len(pages)} class page(s)**, {own} trying a run of their own"
            if pages
            else "No class pages yet."
        )
        put(self.list, content="\n".join([head, *lines]))
        options = (NOBODY, *(f"laptop {page.laptop}" for page in pages))
        if tuple(self.laptop.options) != options:
            keep = self.laptop.value if self.laptop.value in options else NOBODY
            self.laptop.options = options
            self.laptop.value = keep
