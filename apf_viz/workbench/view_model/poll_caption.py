"""A stop's question on the caption (workbench/poll.py): the question and how many answered; on the
presenter's page, on its keys, the room's answers as a bar per choice and the reveal. A class page's
caption shows the question only: the answers of others are never on it."""

from __future__ import annotations

import html

from apf_viz.workbench.poll import Bar, PollView

SPREAD_KEY = "B"  # the bars: how the room answered
REVEAL_KEY = "R"
BAR_PX = 32  # the tallest bar: the bars, their counts and names fit the caption at 1024×768 (a test)
BAR_TEXT_PX = 18  # a bar's count and name: smaller than the words, read from the back all the same
MOST_CELLS = 8  # a cell question's bars: the cells most given (the rest counted as one)
_RIGHT = "#2b8a3e"
_GIVEN = "#4c6ef5"


def answered(poll: PollView) -> str:
    """How many answered, of the seats asked when the server knows them ("12 of 30 answered")."""
    return f"{poll.count} of {poll.present} answered" if poll.present else f"{poll.count} answered"


def poll_html(poll: PollView | None, presenting: bool, mine: str = "") -> str:
    """The question's block of the caption (``""``: no question). ``mine``: on a class page, what its own
    answer is and, after the reveal, whether it was right (workbench/poll.Poll.told)."""
    if poll is None:
        return ""
    asked = f"<b>Question:</b> {html.escape(poll.question)}"
    own = f' · <span data-apf="mine">{html.escape(mine[:1].upper() + mine[1:])}</span>' if mine else ""
    if poll.answer:
        told = f" <b>The run's answer: {html.escape(poll.answer)}</b>"
        told += f" · {poll.right} of {poll.count} gave it" if presenting else own
    elif presenting:
        told = (
            f' · <span data-apf="answered">{answered(poll)}</span> · {SPREAD_KEY} the answers · '
            f"{REVEAL_KEY} reveal"
        )
    elif mine:
        told = f"{own} (change it in the panel, P, or on the canvas)"
    else:
        told = " · answer in the panel (P), or click the canvas"
    bars = bars_html(poll.bars, poll.kind) if presenting else ""
    return f'<div data-apf="question">{asked}{told}</div>{bars}'


def bars_html(bars: tuple[Bar, ...], kind: str) -> str:
    """A bar per choice, its count above it and its name below; the run's answer green once revealed."""
    if not bars:
        return ""
    if kind == "cell" and len(bars) > MOST_CELLS:
        rest = sum(b.count for b in bars[MOST_CELLS:] if not b.right)
        kept = [*bars[:MOST_CELLS], *(b for b in bars[MOST_CELLS:] if b.right)]
        bars = (*kept, Bar("", "other cells", rest, False))
    top = max(1, *(b.count for b in bars))
    columns = "".join(
        f'<div data-apf="bar" data-choice="{html.escape(b.choice)}" data-count="{b.count}" '
        f'style="display:flex;flex-direction:column;align-items:center;min-width:40px;'
        f'font-size:{BAR_TEXT_PX}px;line-height:1.1">'
        f"<div>{b.count}</div>"
        f'<div style="width:30px;height:{max(2, round(BAR_PX * b.count / top))}px;'
        f'background:{_RIGHT if b.right else _GIVEN}"></div>'
        f'<div style="white-space:nowrap">{"✔ " if b.right else ""}{html.escape(_short(b, kind))}</div></div>'
        for b in bars
    )
    return (
        f'<div data-apf="spread" style="display:flex;flex-wrap:wrap;align-items:flex-end;gap:4px 10px">'
        f"{columns}</div>"
    )


def _short(bar: Bar, kind: str) -> str:
    """A bar's name under it: the robot's number, the cell, the light or outcome."""
    if kind == "robot":
        return bar.choice
    return bar.words.replace(" on the grid", "")
