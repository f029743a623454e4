"""The legend (every mark the screen can show, each swatch drawn as the canvas draws it) and the
paper's symbols typeset for the panels; read off what the algorithm describes, never off a particular
algorithm."""

from __future__ import annotations

import html
import re
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from apf_viz.core.portrayal import Cells, Frame, LightStyle
from apf_viz.workbench.palette import MARK_COLORS, PHASE_COLORS, TARGET_COLORS

if TYPE_CHECKING:
    from apf_viz.workbench.view_model.views import SessionView

# H_L^O → H<sub>L</sub><sup>O</sup>; L_I → L<sub>I</sub>; the paper's symbols as a reader knows them.
SYMBOL = re.compile(r"\b([A-Za-z])_(\{[^}]*\}|[A-Za-z0-9]+)(?:\^([A-Za-z]))?")


@dataclass(frozen=True)
class Entry:
    """One legend line: a swatch (its colour and shape: "disc", "tile" (a square robot), "ring", "square",
    "burst", or "none" for
    a mark the canvas writes as a word) and words."""

    color: tuple[int, int, int]
    shape: str
    label: str
    meaning: str = ""


def symbol_html(text: str) -> str:
    """Escape ``text`` and typeset the paper's sub- and superscripts: ``H_L^O`` becomes
    H<sub>L</sub><sup>O</sup>."""

    def typeset(m: re.Match[str]) -> str:
        sub = m.group(2).strip("{}")
        sup = f"<sup>{m.group(3)}</sup>" if m.group(3) else ""
        return f"{m.group(1)}<sub>{sub}</sub>{sup}"

    return SYMBOL.sub(typeset, html.escape(text))


def _light_swatch(style: LightStyle) -> str:
    """A light's swatch shape: its disc, or its square drawn with the robots' outline ("tile")."""
    return "tile" if style.shape == "square" else "disc"


def swatch(color: tuple[int, int, int], shape: str = "disc") -> str:
    """A legend swatch drawn as the canvas draws the mark: a disc, a square, a ring, a square ring, a
    line or a burst."""
    outline = MARK_COLORS["outline"]
    style = {
        "disc": f"border-radius:50%;background:rgb{tuple(color)};border:1.5px solid rgb{outline}",
        "square": f"border-radius:1px;background:rgb{tuple(color)}",
        "tile": f"border-radius:1px;background:rgb{tuple(color)};border:1.5px solid rgb{outline}",
        "ring": f"border-radius:50%;border:3.5px solid rgb{tuple(color)};box-sizing:border-box",
        "line": f"height:3px;margin-bottom:4px;background:rgb{tuple(color)}",
        "square-ring": f"border:3.5px solid rgb{tuple(color)};box-sizing:border-box",
        "diamond": f"background:rgb{tuple(color)};transform:rotate(45deg) scale(0.8)",
    }.get(shape)
    if style is None:  # the collision's burst: viser's "sparkle" point, drawn as the glyph it resembles
        return (
            f'<span style="display:inline-block;flex:none;width:13px;line-height:13px;text-align:center;'
            f'font-size:15px;color:rgb{tuple(color)}">✦</span>'
        )
    return f'<span style="display:inline-block;flex:none;width:13px;height:13px;{style}"></span>'


# The words the panels use, defined once.
WORDS = (
    "<b>(x, y)</b>: a cell in the screen's grid coordinates (x to the right, y up as drawn); robots agree "
    "on x only, and a robot's own y may point down (its diamond). An <b>event</b> is one Look, Compute or "
    "Move of one robot (the Event counter); a <b>step</b> is one choice of the scheduler (the timeline): "
    "one event under ASYNC, a round's Looks, Computes or Moves under FSYNC and SSYNC."
)
UPSIDE_DOWN = (
    "Robots agree only on left and right, so a pattern formed upside down (mirrored in y) counts as formed."
)


def _engine_marks() -> list[tuple[str, str, str]]:
    """The engine's marks, as (swatch, words, what hovering says): the same for every algorithm."""
    c = MARK_COLORS
    return [
        (swatch(PHASE_COLORS["looked"], "ring"), "has looked", "holds a snapshot, has not computed"),
        (swatch(PHASE_COLORS["computed"], "ring"), "has computed", "its light is set, its move pending"),
        (swatch(c["last"], "ring"), "acted last", "the robot of the last event"),
        (swatch(c["selected"], "ring"), "selected", "click a robot to select it"),
        (
            "<b>◆</b>",
            "its own +y",
            "the diamond: the robot's +y, down if the adversary flipped it (many robots: drawn once zoomed "
            "in enough to see it)",
        ),
        (swatch(c["pending"], "line"), "pending move", "many robots: a dot where it goes"),
        (swatch(c["ray"], "line"), "rays: what it saw", "to its snapshot; idle: what it would see now"),
        (
            swatch(c["ghost"], "ring"),
            "ghost 3′: seen there",
            "robot 3 as the selected robot saw it, in the light it saw, since changed (a light-only change:"
            " a small badge beside the robot)",
        ),
        (
            '<b style="font-size:0.85em">stale</b>',
            "snapshot out of date",
            "holds a snapshot in which another robot has moved or relit since",
        ),
        (
            swatch(c["hidden"], "disc"),
            "hidden from selected",
            "greyed: the selected robot does not see it; a small dark square marks the robot that hides it",
        ),
        (
            swatch(c["region"], "square"),
            "Why: regions tested",
            "the regions its last rule tested, each its own colour, numbered as in Why",
        ),
        (
            swatch(c["collision"], "burst"),
            "collision",
            "where a collision happens: the cell a robot moved into",
        ),
        (
            swatch(c["never"], "square-ring"),
            "will never act",
            "stuck: no robot's next cycle changes anything",
        ),
        (swatch(c["axis"], "line"), "symmetry axis", "Edit robots: why a start is unsolvable"),
        (swatch(c["diverged"], "diamond"), "diverges here", "Compare: the robot whose event first differs"),
    ]


_last_legend: list[Any] = [None, None, ""]  # (legend, overlays, html): the last inputs, by identity


def legend_html(view: SessionView) -> str:
    """Every mark the screen can show, in two columns: the algorithm's lights (their meaning on hover)
    and overlays, then the engine's marks, each swatch drawn as the canvas draws it. Every page's view
    of one frame holds the run's very legend and overlays: the table is made once for them all."""
    legend, overlays, made = _last_legend
    if view.legend is legend and view.overlays is overlays:
        return str(made)
    made = _legend_html(view)
    _last_legend[:] = [view.legend, view.overlays, made]
    return made


def _legend_html(view: SessionView) -> str:
    cells = [
        (
            swatch(style.color, _light_swatch(style)),
            f"<b>{html.escape(light)}</b>"
            + (f' <span style="color:#555">{symbol_html(style.meaning)}</span>' if style.meaning else ""),
            style.meaning or "",
        )
        for light, style in view.legend.items()
    ]
    for mark in view.overlays.marks:  # in the colours the scene draws them
        if isinstance(mark, Cells):
            cells.append((swatch(TARGET_COLORS[mark.style], "square"), symbol_html(mark.label), ""))
        else:
            color = (
                getattr(mark, "color", None) or MARK_COLORS["frame" if isinstance(mark, Frame) else "line"]
            )
            cells.append((swatch(color, "line"), symbol_html(mark.label), ""))
    cells += _engine_marks()
    row = "display:flex;align-items:center;gap:5px;min-width:0"
    clip = "white-space:nowrap;overflow:hidden;text-overflow:ellipsis"
    wide = ";grid-column:1 / -1"
    lights = len(view.legend)  # a light's row spans both columns: its meaning is read aloud in a lecture
    body = "".join(
        f'<div title="{html.escape(tip, quote=True)}" style="{row}{wide if i < lights else ""}">'
        f'{swatch}<span style="{"" if i < lights else clip}">{text}</span></div>'
        for i, (swatch, text, tip) in enumerate(cells)
    )
    columns = "display:grid;grid-template-columns:minmax(0,1fr) minmax(0,1fr);gap:2px 8px"
    grid = f'<div style="{columns}">{body}</div>'
    return (
        f'<div style="font-size:0.8em">{grid}<div style="margin-top:4px;color:#555">{UPSIDE_DOWN}</div>'
        f'<div style="margin-top:4px;color:#555">{WORDS}</div></div>'
    )


def slide_legend(view: SessionView) -> list[Entry]:
    """The legend of a saved slide: the lights in use, then only the marks the picture shows."""
    c = MARK_COLORS
    out = [
        Entry(style.color, _light_swatch(style), light, plain(style.meaning))
        for light, style in ((light, view.legend.get(light)) for light in view.lights_in_use)
        if style is not None
    ]
    marks = (
        (bool(view.targets), Entry(TARGET_COLORS["placed"], "square", "target cells")),
        (view.selected is not None, Entry(c["selected"], "ring", f"selected: robot {view.selected}")),
        (bool(view.ghosts), Entry(c["ghost"], "ring", "ghost: where the selected robot saw a robot")),
        (bool(view.hidden), Entry(c["hidden"], "disc", "greyed: hidden from the selected robot")),
        (
            bool(view.stale_holders),
            Entry(c["ghost"], "none", "“stale” beside a robot: it holds an out-of-date snapshot"),
        ),
        (view.collision is not None, Entry(c["collision"], "burst", "collision")),
        (bool(view.never_act), Entry(c["never"], "square", "will never act")),
    )
    return out + [entry for shown, entry in marks if shown]


def slide_caption(view: SessionView) -> list[str]:
    """A saved slide's caption: the stage, the last event, the outcome located."""
    lines = [plain(view.stage)] if view.stage else []
    last = view.last_events[0] if view.last_events else "the start"
    lines.append(f"Event {view.event} · {plain(last)} · {len(view.robots)} robots, {view.algorithm}")
    if view.outcome:
        where = f": {plain(view.collision[0])}" if view.collision else ""
        lines.append(f"{view.outcome.upper()}{where}")
    return lines


def plain(text: str) -> str:
    """The paper's symbols as plain text (``L_1`` → ``L₁``), as the canvas writes them."""
    return canvas_symbol(text)


# The canvas shows plain text: the paper's sub- and superscripts as Unicode where Unicode has them.
# Unicode has no subscript B: a small capital stands in for it, so that H_B^C is set like H_U^C beside
# it on the canvas, not written raw.
_SUBSCRIPTS = {
    "L": "ₗ", "I": "ᵢ", "V": "ᵥ", "H": "ₕ", "U": "ᵤ", "1": "₁", "0": "₀", "2": "₂", "j": "ⱼ", "n": "ₙ",
    "−": "₋", "B": "ʙ",
}  # fmt: skip
_SUPERSCRIPTS = {"O": "ᴼ", "C": "ᶜ"}


def canvas_symbol(text: str) -> str:
    """``H_L^O`` → ``Hₗᴼ``, ``L_H1`` → ``Lₕ₁``: the panel's typesetting (the same symbols as
    :func:`symbol_html`) in Unicode. A label with a symbol Unicode cannot set whole (there is no
    subscript R) is written as the paper's source writes it: never half set."""

    def settable(m: re.Match[str]) -> bool:
        sub, sup = m.group(2).strip("{}"), m.group(3) or ""
        return all(c in _SUBSCRIPTS for c in sub) and all(c in _SUPERSCRIPTS for c in sup)

    def typeset(m: re.Match[str]) -> str:
        sub, sup = m.group(2).strip("{}"), m.group(3) or ""
        return m.group(1) + "".join(_SUBSCRIPTS[c] for c in sub) + "".join(_SUPERSCRIPTS[c] for c in sup)

    if not all(settable(m) for m in SYMBOL.finditer(text)):
        return text  # one label, one notation: all as the source writes them
    return SYMBOL.sub(typeset, text)
