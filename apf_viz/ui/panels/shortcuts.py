"""Keyboard shortcuts (viser's command palette, Ctrl/Cmd+K, lists them too): a lecture is driven from the
keyboard or a presenter's clicker, with the panel collapsed if need be. Each browser has its own, and
what a shortcut has to say goes to that browser only."""

from __future__ import annotations

from collections.abc import Callable

from apf_viz.ui.panels.context import PanelContext
from apf_viz.workbench.view_model import SessionView

# (label, key, what it does). A presenter's clicker sends PageDown / PageUp. The arrows (and W A S D Q E)
# are the camera's own in viser, held to orbit: a step on → would also turn the view.
SHORTCUTS = (
    ("Play / Pause", "space", "play the run, or pause it"),
    ("Step", "enter", "one event (Manual: the selected robot's next phase)"),
    ("Back", "backspace", "one event back"),
    ("Next stage", "pagedown", "run until the algorithm's stage changes (a lecture: its next stop)"),
    ("Previous stage", "pageup", "back to where the previous stage began (a lecture: its previous stop)"),
    ("Next move", "M", "run until some robot moves"),
    ("Frame run", "F", "point this browser's camera at the whole run"),
)  # and P, presentation mode (ui/panels/presentation.py)


# A stop's message replaces the previous stop's, whichever way the lecture went (ui/panels/context.tell).
NOTE_TITLES = {"Next stage": "Stage", "Previous stage": "Stage", "Next move": "Move"}


class Shortcuts:
    def __init__(self, gui, ctx: PanelContext) -> None:
        actions: dict[str, Callable] = {
            "Play / Pause": lambda e: ctx.session.toggle_play(),
            "Step": ctx.step,
            "Back": lambda e: ctx.session.back(),
            "Next stage": lambda e: self._next(ctx, forward=True),
            "Previous stage": lambda e: self._next(ctx, forward=False),
            "Next move": lambda e: ctx.session.run_until("move"),
            "Frame run": lambda e: ctx.frame(e.client) if e.client is not None else None,
        }
        for label, key, text in SHORTCUTS:
            command = gui.add_command(label, description=text, hotkey=key)
            command.on_trigger(
                ctx.guard(actions[label], NOTE_TITLES.get(label, label), mine=label == "Frame run")
            )

    def _next(self, ctx: PanelContext, forward: bool) -> str | None:
        """PageDown / PageUp: a guided lecture's next or previous stop when one is loaded, else the run's
        next or previous stage."""
        s = ctx.session
        if s.lecturer is not None:
            said = s.next_stop() if forward else s.previous_stop()
            return None if ctx.presenting() and "not reached" not in said else said
        return self._stop(ctx, s.run_until("stage") if forward else s.back_to_stage())

    @staticmethod
    def _stop(ctx: PanelContext, said: str) -> str | None:
        """What a stage stop has to tell: nothing in presentation mode when it reached a stage (the
        caption on the canvas names it; a message would cover it), else the message."""
        view = ctx.view()
        reached = said.startswith(view.stage) or bool(view.outcome and said.startswith(view.outcome))
        return None if reached and ctx.presenting() else said

    def refresh(self, view: SessionView) -> None:
        pass  # a shortcut shows nothing of its own
