"""A lecture stop's question (workbench/poll.py). On a class page, the Question folder, first in its
panel: the question, this page's answer (a choice, or a cell typed or clicked on the canvas), changed at
will until the reveal, then the run's answer and whether this page gave it; nobody else's answer is ever
sent to it. On the presenter's page, two keys: B shows the room's answers on the caption, R reveals."""

from __future__ import annotations

from apf_viz.ui.panels.context import PanelContext, put
from apf_viz.ui.seat import seat_js
from apf_viz.workbench.poll import Poll
from apf_viz.workbench.question import choice_words
from apf_viz.workbench.view_model import SessionView
from apf_viz.workbench.view_model.poll_caption import REVEAL_KEY, SPREAD_KEY

NONE = "—"
TAP_MOST = 12
"""A question of at most this many choices is answered by one tap on its button (a phone, a laptop alike);
more go in a dropdown."""


class QuestionFolder:
    def __init__(self, gui, ctx: PanelContext) -> None:
        self.ctx = ctx
        offer = ctx.seat_offer()
        if offer is not None:  # a class page without a seat: it keeps this one and goes to its address
            gui.add_html(seat_js(offer))
        self.folder = gui.add_folder("Question", order=-1.0, visible=False)
        with self.folder:
            self.text = gui.add_markdown("")
            self.tap = gui.add_button_group("Tap your answer", (NONE,), visible=False)
            self.choice = gui.add_dropdown("Your answer", (NONE,), initial_value=NONE)
            self.cell = gui.add_text(
                "Your cell", initial_value="", hint="x, y on the grid; or click the cell"
            )
            self.give_cell = gui.add_button("Answer this cell")
        self.choice.on_update(ctx.from_browser(self._chosen, "Question", mine=True))
        self.tap.on_click(ctx.guard(lambda e: self._give(self._words.get(e.target.value, NONE)), "Question",
                                    mine=True))  # fmt: skip
        self.give_cell.on_click(ctx.guard(lambda e: self._give(self.cell.value), "Question", mine=True))
        self._words: dict[str, str] = {}  # a choice's words on the dropdown -> the choice
        self._kind: tuple | None = None  # the poll the controls were last laid out for
        for label, key, text, act in (
            ("The room's answers", SPREAD_KEY, "show or hide how the class answered the stop's question",
             lambda s: s.toggle_spread()),
            ("Reveal the answer", REVEAL_KEY, "play the run to the question's answer, and mark it",
             lambda s: s.reveal()),
        ):  # fmt: skip
            command = gui.add_command(label, description=text, hotkey=key)
            command.on_trigger(ctx.guard(self._presenter_only(act), "Question", mine=True))

    def _presenter_only(self, act):
        def run(event) -> str | None:
            shared = self.ctx.shared
            if not self.ctx.classroom.is_presenter(self.ctx.browser):
                return "the presenter shows the answers and reveals them"
            said = act(shared)
            return None if self.ctx.presenting() else said  # the caption says it; a notice would cover robots

        return run

    def _chosen(self, event) -> str | None:
        value = self.choice.value
        return None if value == NONE else self._give(self._words.get(value, value))

    def _give(self, choice: str) -> str:
        return self.ctx.classroom.answer(self.ctx.browser, choice)

    def refresh(self, view: SessionView) -> None:
        poll = self.ctx.shared.screen.poll
        shown = poll is not None and not self.ctx.classroom.is_presenter(self.ctx.browser)
        put(self.folder, visible=shown)
        if not shown or poll is None:
            return
        self._lay_out(poll)
        mine = poll.given(self.ctx.answer_key())
        said = choice_words(poll.kind, mine) if mine is not None else ""
        if poll.revealed:
            told = poll.told(self.ctx.answer_key())
            verdict = f"{told[:1].upper()}{told[1:]}." if mine else ""
            text = f"**{poll.question}**\n\nThe run's answer: **{poll.answer.words()}**. {verdict}"
        else:
            tap = poll.choices is not None and len(poll.choices) <= TAP_MOST
            robot = "Tap a robot, or its button" if tap else "Click a robot, or choose it"
            how = {"robot": robot, "cell": "Tap the cell, or type it"}.get(
                poll.kind, "Tap one" if tap else "Choose"
            )
            held = f"Your answer: **{said}** (change it until the reveal)." if mine else "Not answered yet."
            text = f"**{poll.question}**\n\n{how}. {held}"
        put(self.text, content=text)
        few = poll.choices is not None and len(poll.choices) <= TAP_MOST
        put(self.tap, visible=few and not poll.revealed)
        put(self.choice, visible=poll.choices is not None and not few and not poll.revealed)
        put(self.cell, visible=poll.choices is None and not poll.revealed)
        put(self.give_cell, visible=poll.choices is None and not poll.revealed)
        if poll.choices is not None:
            put(self.choice, value=choice_words(poll.kind, mine) if mine is not None else NONE)

    def _lay_out(self, poll: Poll) -> None:
        """The dropdown's choices, for this question (laid out once a question)."""
        key = (id(poll), poll.choices)
        if key == self._kind:
            return
        self._kind = key
        self._words = {choice_words(poll.kind, c): c for c in poll.choices or ()}
        self.choice.options = (NONE, *self._words)
        if self._words:
            self.tap.options = tuple(self._words)
        self.choice.value = NONE
        self.cell.value = ""
