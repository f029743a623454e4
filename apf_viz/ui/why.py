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
    else:
        lines.append("_This algorithm does not explain its decisions._")
    if why.regions:
        lines.append("Regions it looked at are shaded blue on the grid, in its own frame.")
    return "\n\n".join(lines)


def _swatch(color: tuple[int, int, int], shape: str = "disc") -> str:
    radius = "6px" if shape == "disc" else "1px"
    return (
        f'<span style="display:inline-block;width:12px;height:12px;border-radius:{radius};'
        f'background:rgb{tuple(color)}"></span>'
    )


def legend_html(view: SessionView) -> str:
    """Every mark the screen can show: the algorithm's lights and overlays, then the engine's marks."""
    rows = [
        f"{_swatch(style.color)} <b>{html.escape(light)}</b>"
        + (f" — {symbol_html(style.meaning)}" if style.meaning else "")
        for light, style in view.legend.items()
    ]
    for mark in view.overlays.marks:  # in the colours the scene draws them
        if isinstance(mark, Cells):
            color = TARGET_COLORS[mark.style]
        else:
            color = (
                getattr(mark, "color", None) or MARK_COLORS["frame" if isinstance(mark, Frame) else "line"]
            )
        rows.append(f"{_swatch(color, 'square')} {symbol_html(mark.label)}")
    c = MARK_COLORS
    rows += [
        f"{_swatch(PHASE_COLORS['looked'], 'square')} halo: has looked · "
        f"{_swatch(PHASE_COLORS['computed'], 'square')} has computed",
        "nose (many robots: grey diamond): the robot's own +y, down if flipped by the adversary",
        f"{_swatch(c['pending'], 'square')} a computed move (many robots: a dot where it goes)",
        f"{_swatch(c['ray'], 'square')} rays: what the selected robot sees · "
        f"{_swatch(c['ghost'])} ghosts: where its snapshot saw them",
        f"{_swatch(c['region'], 'square')} Why: the regions its last rule tested",
        f"{_swatch(c['last'])} the robot that acted last · {_swatch(c['selected'])} the selected robot",
        f"{_swatch(c['collision'])} where a collision happened",
        f"{_swatch(c['axis'], 'square')} Edit robots: the symmetry axis of an unsolvable start",
    ]
    body = "".join(f'<div style="margin:2px 0">{row}</div>' for row in rows)
    return f'<div style="font-size:0.85em">{body}</div>'
