"""Presentation mode's caption, set for a projector read from the back of a room: a lecture stop's title
and words, and one stage line, at sizes that are never shrunk; what does not fit beside them (who waits
on what, the last event, the lights' meanings, the keys) is one key away, on the same strip (I, details).

The sizes are the caption's contract (tests/test_lecture_projector.py measures them in a browser): a
title of TITLE_PX, every other word at WORDS_PX or more."""

from __future__ import annotations

import html
from typing import TYPE_CHECKING

from apf_viz.workbench.view_model.legend import symbol_html
from apf_viz.workbench.view_model.poll_caption import REVEAL_KEY, SPREAD_KEY, poll_html

if TYPE_CHECKING:
    from apf_viz.workbench.view_model.views import SessionView

TITLE_PX = 28
WORDS_PX = 20
DETAILS_KEY = "I"  # D, the obvious key, is viser's: it moves the camera (WASD)

_QUIET = "color:#555"

# What the page is, and its keys (the panel that would list them is collapsed): shown with the details.
KEYS = {
    "presenting": "<b>Presenting</b> · P the panel · PageDown / PageUp next / previous stop · Enter step · "
    "Space play · I details · J the class address · "
    + f"{SPREAD_KEY} a question's answers · {REVEAL_KEY} its reveal · "
    + "Esc gives the keys back from a field · Ctrl+K every key",
    "following": "<b>Following the lecture</b>: the presenter's keys drive the run · P the panel · F frame "
    "the run · I details · Try it yourself (in the panel) for a run of your own",
    "class-drives": "<b>The presenter lets the class drive</b> · P the panel · Enter step · Space play · "
    "I details",
    "own": "<b>Your own run</b> · the projector is untouched · P the panel · Enter step · Backspace back · "
    "Space play · I details · Back to the lecture (in the panel)",
}
_PAGE_NAMES = {
    "presenting": "Presenting",
    "following": "Following the lecture",
    "class-drives": "The class drives",
    "own": "Your own run",
}


def caption_html(
    view: SessionView, page: str = "presenting", details: bool = False, mine: str = "", who: str = ""
) -> str:
    """The caption: a lecture stop's words (or, without a lecture, the run's state and its lights), else
    with ``details`` everything else the run has to say. ``page``: a key of :data:`KEYS`; ``mine``: a
    class page's own answer to the stop's question, and whether it was right once revealed; ``who``: the
    page's name in the room ("laptop 7"), first on its top line."""
    body = _details(view, page) if details else _words(view, page, mine, who)
    kind = "details" if details else "words"
    return f'<div data-apf="{kind}" style="font-size:{WORDS_PX}px;line-height:1.3">{body}</div>'


def _words(view: SessionView, page: str, mine: str = "", who: str = "") -> str:
    hint = f"{DETAILS_KEY}: details"
    named = f"<b>{html.escape(who)}</b> · " if who else ""
    if view.lecture is not None:
        where, title, say = view.lecture
        asked = poll_html(view.poll, page == "presenting", mine)
        # The bars take the words' room: the room has heard them by the time it sees how it answered.
        words = (
            ""
            if view.poll is not None and view.poll.bars
            else f'<div data-apf="say">{symbol_html(say)}</div>'
        )
        return (
            f'<div style="{_QUIET}">{named}{html.escape(where)} · {hint}</div>'
            f"{_title(symbol_html(title))}{words}{asked}{_status(view)}"
        )
    return (
        f'<div style="{_QUIET}">{named}{_PAGE_NAMES.get(page, page)} · {hint}, and the keys</div>'
        f"{_title(symbol_html(view.stage_line))}"
        f"<div>{_event_line(view)}</div>{_compared(view)}{_lights(view, meanings=False)}"
    )


def _details(view: SessionView, page: str) -> str:
    """Everything the words leave out: the outcome located and explained, Compare's two sides, the last
    event, the lights and their meanings, the page's keys. Scrolled, never shrunk, when it is long."""
    where = view.lecture[0] if view.lecture is not None else _PAGE_NAMES.get(page, page)
    return (
        f'<div style="{_QUIET}">{html.escape(where)} · details · {DETAILS_KEY}: back to the words</div>'
        f'<div style="font-weight:bold">{symbol_html(view.stage_line)}</div>{_why(view)}'
        f"{_compared(view)}<div>{_event_line(view)}</div>{_lights(view, meanings=True)}"
        f'<div style="{_QUIET}">{KEYS.get(page, "")}</div>'
    )


def _title(text: str) -> str:
    return (
        f'<div data-apf="title" style="font-size:{TITLE_PX}px;font-weight:bold;line-height:1.2">{text}</div>'
    )


def _status(view: SessionView) -> str:
    """The stop's one line of state: the stage line (the outcome once there is one), Compare's other side,
    and the event."""
    other = ""
    if view.compare is not None:
        c = view.compare
        other = f" · right: {c.outcome.upper() if c.outcome else 'running'}"
    return (
        f'<div data-apf="status" style="font-weight:bold">{symbol_html(view.stage_line)}{other} · '
        f"event {view.event}</div>"
    )


def _event_line(view: SessionView) -> str:
    last = html.escape(view.last_events[0]) if view.last_events else "the start"
    note = f" · <i>{html.escape(view.note_here)}</i>" if view.note_here else ""
    return f"Event {view.event} · {last}{note}"


def _why(view: SessionView) -> str:
    """A failure located and explained: where it collided, whose stale decision, or who waits on what."""
    lines = []
    if view.collision:
        lines.append(html.escape(view.collision[0]))
    why = view.fatal[0] or view.waits
    if why:
        lines.append(symbol_html(why).replace("\n", "<br>"))
    if view.endless is not None:
        lines.append(html.escape(view.endless[1]))
    return "".join(f"<div>{line}</div>" for line in lines)


def _compared(view: SessionView) -> str:
    """Compare: how each side stands, in words (the left run's verdict alone would tell half the story)."""
    other = view.compare
    if other is None:
        return ""

    def side(name: str, v: SessionView) -> str:
        state = v.outcome.upper() if v.outcome else f"running (event {v.event})"
        return f"<b>{name}</b> {html.escape(v.algorithm_title or v.algorithm)}: <b>{state}</b>"

    part = ""
    if view.divergence is not None:  # on the canvas, a diamond on that robot in both runs
        part = f" · they decide differently at event {view.divergence[0]}, robot {view.divergence[2]} (◆)"
    return f"<div>{side('left', view)} · {side('right', other)}{part}</div>"


def _lights(view: SessionView, meanings: bool) -> str:
    """The lights in use, each with its swatch: a wrapped row of names, or a line each with its meaning."""
    size = WORDS_PX - 4
    named = [
        f'<span style="display:inline-block;width:{size}px;height:{size}px;border-radius:50%;'
        f"background:rgb{tuple(view.legend[light].color)};border:1.5px solid #555;"
        f'vertical-align:-2px;margin-right:6px"></span><b>{html.escape(light)}</b>'
        + (f' <span style="color:#444">{symbol_html(view.legend[light].meaning)}</span>' if meanings else "")
        for light in view.lights_in_use
        if light in view.legend
    ]
    if meanings:
        return "".join(f"<div>{n}</div>" for n in named)
    row = "".join(f"<span>{n}</span>" for n in named)
    return f'<div style="display:flex;flex-wrap:wrap;gap:0 18px">{row}</div>'
