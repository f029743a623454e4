"""Text for the panels: the `Why` panel (the selected robot's last decision and the predicates its rule
tested) and the legend, both read off what the algorithm describes, never off a particular algorithm."""

from __future__ import annotations

import html
import re

from apf_viz.core.portrayal import Cells, Frame
from apf_viz.ui.scene import MARK_COLORS, PHASE_COLORS, TARGET_COLORS
from apf_viz.ui.session import SessionView

# H_L^O → H<sub>L</sub><sup>O</sup>; L_I → L<sub>I</sub>; the paper's symbols as a reader knows them.
_SYMBOL = re.compile(r"\b([A-Za-z])_(\{[^}]*\}|[A-Za-z0-9]+)(?:\^([A-Za-z]))?")


def symbol_html(text: str) -> str:
    """Escape ``text`` and typeset the paper's sub- and superscripts: ``H_L^O`` becomes
    H<sub>L</sub><sup>O</sup>."""

    def typeset(m: re.Match) -> str:
        sub = m.group(2).strip("{}")
        sup = f"<sup>{m.group(3)}</sup>" if m.group(3) else ""
        return f"{m.group(1)}<sub>{sub}</sub>{sup}"

    return _SYMBOL.sub(typeset, html.escape(text))


def _value(value: object) -> str:
    if value is True:
        return "✔ yes"
    if value is False:
        return "✘ no"
    return html.escape(str(value))


def why_markdown(view: SessionView) -> str:
    """The selected robot's last decision: rule id and text, then each predicate with its value."""
    why = view.why
    if why is None:
        return "Select a robot to see why it acted."
    head = f"**Robot {why.robot}**"
    if why.explanation is None:
        return f"{head} has not decided yet: its first Compute will."
    d = why.explanation.decision
    move = d.move.value if d.move is not None else "stay"
    lines = [
        f"{head} · rule <code>{html.escape(d.rule_id or '—')}</code>",
        f"{symbol_html(d.rule)}",
        f"→ light <code>{html.escape(d.light)}</code>, move: {move} (its own frame)",
    ]
    if why.holds_snapshot:
        lines.append("_It has looked again since: its next Compute decides anew._")
    if why.changed:
        shown = "; ".join(why.changed[:4]) + (
            f"; and {len(why.changed) - 4} more" if len(why.changed) > 4 else ""
        )
        lines.append(
            "⚠ **Decided on an older view.** Since the Look this decision used, robots it saw changed: "
            f"{shown}. The predicates below are about that view."
        )
    if why.explanation.predicates:
        rows = "".join(
            f"<tr><td>{symbol_html(p.symbol)}</td><td>{_value(p.value)}</td>"
            f"<td>{symbol_html(p.meaning)}</td></tr>"
            for p in why.explanation.predicates
        )
        lines.append(
            '<table style="font-size:0.9em"><tr><th>tested</th><th>value</th><th>meaning</th></tr>'
            f"{rows}</table>"
        )
    elif not d.rule_id:
        lines.append("_This algorithm does not explain its decisions._")
    else:
        lines.append("_No predicates are listed for this rule._")
    if why.regions:
        lines.append(
            "Regions it looked at are shaded blue on the grid, in its own frame, where it stood when it "
            "looked (they stay there when it moves)."
        )
    if why.now is not None:
        n = why.now
        now_move = n.move.value if n.move is not None else "stay"
        idle = (
            "its next cycle would change nothing" if n.light == d.light and n.move is None else "it will act"
        )
        lines.append(
            f"**If it looked now:** rule <code>{html.escape(n.rule_id or '—')}</code> → light "
            f"<code>{html.escape(n.light)}</code>, move: {now_move}: {idle}."
        )
    return "\n\n".join(lines)


def _swatch(color: tuple[int, int, int], shape: str = "disc") -> str:
    """A legend swatch drawn as the canvas draws the mark: a disc, a square, a ring or a line."""
    outline = MARK_COLORS["outline"]
    style = {
        "disc": f"border-radius:50%;background:rgb{tuple(color)};border:1.5px solid rgb{outline}",
        "square": f"border-radius:1px;background:rgb{tuple(color)}",
        "ring": f"border-radius:50%;border:3.5px solid rgb{tuple(color)};box-sizing:border-box",
        "line": f"height:3px;margin-bottom:4px;background:rgb{tuple(color)}",
    }[shape]
    return f'<span style="display:inline-block;flex:none;width:13px;height:13px;{style}"></span>'


UPSIDE_DOWN = (
    "Robots agree only on left and right, so a pattern formed upside down (mirrored in y) counts as formed."
)


def legend_html(view: SessionView) -> str:
    """Every mark the screen can show, in two columns: the algorithm's lights (their meaning on hover)
    and overlays, then the engine's marks, each swatch drawn as the canvas draws it."""
    cells = [
        (
            _swatch(style.color),
            f"<b>{html.escape(light)}</b>"
            + (f' <span style="color:#555">{symbol_html(style.meaning)}</span>' if style.meaning else ""),
            style.meaning or "",
        )
        for light, style in view.legend.items()
    ]
    for mark in view.overlays.marks:  # in the colours the scene draws them
        if isinstance(mark, Cells):
            cells.append((_swatch(TARGET_COLORS[mark.style], "square"), symbol_html(mark.label), ""))
        else:
            color = (
                getattr(mark, "color", None) or MARK_COLORS["frame" if isinstance(mark, Frame) else "line"]
            )
            cells.append((_swatch(color, "line"), symbol_html(mark.label), ""))
    c = MARK_COLORS
    cells += [
        (_swatch(PHASE_COLORS["looked"], "ring"), "has looked", "holds a snapshot, has not computed"),
        (_swatch(PHASE_COLORS["computed"], "ring"), "has computed", "its light is set, its move pending"),
        (_swatch(c["last"], "ring"), "acted last", "the robot of the last event"),
        (_swatch(c["selected"], "ring"), "selected", "click a robot to select it"),
        ("<b>◆</b>", "its own +y", "the diamond: the robot's +y, down if the adversary flipped it"),
        (_swatch(c["pending"], "line"), "pending move", "many robots: a dot where it goes"),
        (_swatch(c["ray"], "line"), "rays: what it saw", "to its snapshot; idle: what it would see now"),
        (
            _swatch(c["ghost"], "ring"),
            "ghost: seen there",
            "a robot it saw, in the light it saw, since changed",
        ),
        (_swatch(c["region"], "square"), "Why: regions tested", "the regions its last rule tested"),
        (_swatch(c["collision"]), "collision", "the cell and robots of a collision"),
        (_swatch(c["never"], "ring"), "will never act", "stuck: no robot's next cycle changes anything"),
        (_swatch(c["axis"], "line"), "symmetry axis", "Edit robots: why a start is unsolvable"),
    ]
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
        f'<div style="font-size:0.8em">{grid}<div style="margin-top:4px;color:#555">{UPSIDE_DOWN}</div></div>'
    )
