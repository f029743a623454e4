"""Presentation mode (P, or the Run folder's button): this browser's panel collapses and a large caption
floats over the bottom of the canvas — a lecture stop's words, the stage, the last event, a failure's
outcome, the lights in use — while the keyboard drives the run (ui/panels/shortcuts.py). Another
browser's screen is not touched.

The caption is set for the back of a room (workbench/view_model/caption.py): its sizes are never
shrunk to fit.
It spans the canvas's width, at most CAPTION_ROOM of its height, and the camera leaves that share free;
I swaps a stop's words for the details (who waits on what, the last event, the lights, the keys) on the
same strip, in this browser only. Each new caption starts at its top (a scroll never carries over to the
next stop). It sits at the bottom: the page's notifications appear at the top left."""

from __future__ import annotations

import zlib

import viser

from apf_viz.ui.caption_room import CAPTION_ROOM
from apf_viz.ui.panels.context import PanelContext
from apf_viz.ui.recorder import canvas_size
from apf_viz.workbench.view_model import SessionView
from apf_viz.workbench.view_model.caption import DETAILS_KEY, caption_html


def steady_size(seen: tuple[int, int] | None, reported: tuple[int, int]) -> tuple[int, int]:
    """The canvas's (height, width) to lay the caption out for: the largest reported at this shape.
    Under load viser's client draws at a lower resolution (its adaptive pixel ratio, ¾ to 1 of the
    screen's) and reports that smaller canvas, though the page has not changed size: a caption fitted
    to it ran 22–33 px past its box at 1024×768. Another shape (the window resized) starts afresh."""
    if seen is None or abs(reported[1] * seen[0] - seen[1] * reported[0]) > 0.01 * seen[0] * reported[0]:
        return reported
    return reported if reported[1] > seen[1] else seen


CAPTION_MAX_WIDTH = 1100  # px: wider lines are hard to follow from the back of a room
PHONE_PX = 576
"""A page at most this many CSS pixels wide is a phone held upright: viser's client shows its panel as a
sheet at the bottom and no floating panel (Mantine's ``xs`` breakpoint), so the caption goes first in
that sheet instead. The canvas is reported in device pixels (viser caps their ratio at 2) and, on a
phone, takes the whole screen: at most twice this wide and half as tall again as wide (a projector's
canvas beside the docked panel, 640 × 768 at 1024 × 768, is not one)."""
PHONE_TALL = 1.5


def upright_phone(height: int, width: int) -> bool:
    return 16 < width <= 2 * PHONE_PX and height >= PHONE_TALL * width


MARGIN = 10  # px between the caption and the canvas's edges

# Runs in the page each time the caption changes (an image that fails to load runs its onerror; a new
# caption is a new image): back to the top of the caption's scrolling box.
TO_TOP = (
    '<img alt="" src="data:,{key}" style="display:none" onerror="'
    "var b=this.parentElement;"
    "while(b&&!/(auto|scroll)/.test(getComputedStyle(b).overflowY))b=b.parentElement;"
    'if(b)b.scrollTop=0;">'
)


class Presentation:
    def __init__(self, gui, ctx: PanelContext) -> None:
        self.gui, self.ctx = gui, ctx
        self.panel: viser.PanelHandle | None = None
        self.inline: viser.GuiHtmlHandle | None = None  # the caption first in the panel, on a phone
        self.html: viser.GuiHtmlHandle | None = None
        self._placed: tuple[int, int] | None = None  # the caption's (width, height) last sent
        self._canvas: tuple[int, int] | None = None  # the canvas laid out for (steady_size)
        self.details = False  # the caption shows the details, not the stop's words (I)
        self._stop: tuple[str, str] | None = None  # the lecture stop shown: a new one opens on its words
        command = gui.add_command(
            "Presentation mode", description="collapse the panel; a large caption on the canvas", hotkey="P"
        )
        command.on_trigger(ctx.guard(self.toggle, mine=True))
        details = gui.add_command(
            "Caption details",
            description="the caption's details: waits, last event, lights, keys",
            hotkey=DETAILS_KEY,
        )
        details.on_trigger(ctx.guard(self.toggle_details, mine=True))
        ctx.toggle_presentation = self.toggle
        ctx.presenting = lambda: self.on

    def fit(self, client) -> None:
        """The caption across the bottom of this browser's canvas (as it reports its size; a page that has
        not reported yet gets a 1024×768 projector's)."""
        if self.panel is None:
            return
        height, width = canvas_size(client) if client is not None else (0, 0)
        if width <= 16:  # not reported yet
            height, width = 768, 1024
        self._canvas = height, width = steady_size(self._canvas, (height, width))
        placed = (min(width - 2 * MARGIN, CAPTION_MAX_WIDTH), int(CAPTION_ROOM * height) - MARGIN)
        if placed != self._placed:
            self._placed = placed
            self.panel.float(x=MARGIN, y=-MARGIN, width=placed[0], height=placed[1])

    def toggle_details(self, event=None) -> None:
        """The stop's words or the details, in this browser's caption (nothing without a caption)."""
        if self.on:
            self.details = not self.details
            self.ctx.changed()

    @property
    def on(self) -> bool:
        return self.panel is not None or self.inline is not None

    def toggle(self, event=None) -> None:
        self.present(not self.on, event.client if event is not None else None)

    def present(self, on: bool, client=None) -> None:
        """Presentation mode on or off in this browser (``client``: its canvas, to size the caption)."""
        if on == self.on:
            return
        if on and client is not None and upright_phone(*canvas_size(client)):  # first in the phone's sheet
            self.inline = self.html = self.gui.add_html("", order=-2.0)
        elif on:
            self.gui.main_panel.minimize()
            self.panel = panel = self.gui.add_panel()
            with panel.add_tab("Caption"):
                self.html = self.gui.add_html("")
            self._placed = self._canvas = None
            self.fit(client)
        else:
            if self.panel is not None:
                self.panel.remove()
                self.gui.main_panel.expand()
            if self.inline is not None:
                self.inline.remove()
            self.panel = self.inline = self.html = None
        if client is not None:
            self.ctx.frame(client)  # the caption's room at the bottom comes and goes
        self.ctx.changed()

    def _page(self) -> str:
        """What this page is, for its caption: presenting, following, driving with the class, its own."""
        if self.ctx.in_own_run():
            return "own"
        if self.ctx.state.role == "presenter":
            return "presenting"
        return "class-drives" if self.ctx.drives() else "following"

    def _mine(self) -> str:
        """This page's own answer to the stop's question (kept under its seat: a reload keeps it)."""
        poll = self.ctx.shared.screen.poll
        return poll.told(self.ctx.answer_key()) if poll is not None else ""

    def refresh(self, view: SessionView) -> None:
        if self.html is not None:
            stop = view.lecture[:2] if view.lecture is not None else None
            if stop != self._stop:
                self._stop, self.details = stop, False
            page = self._page()
            laptop = self.ctx.laptop()
            words = caption_html(
                view,
                page,
                self.details,
                self._mine() if page != "presenting" else "",
                f"laptop {laptop}" if laptop is not None else "",
            )
            content = words + TO_TOP.format(key=zlib.crc32(words.encode()))
            if self.html.content != content:
                self.html.content = content
