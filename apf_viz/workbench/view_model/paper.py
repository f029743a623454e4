"""The Paper panel: the algorithm's pseudocode as its paper writes it (core/portrayal.py ``Pseudocode``),
with the line a decision came from highlighted, the conditions it sits in marked, and each resolution's
line in its own colour with its name and reason. Read off what the algorithm describes: no particular
algorithm here."""

from __future__ import annotations

import html

from apf_viz.core.portrayal import CodeBlock, CodeLine, Pseudocode, pseudocode_of
from apf_viz.workbench.view_model.legend import symbol_html

HIT = "#ffe680"  # the decision's line
WITHIN = "#fff6cc"  # the conditions it sits in
RESOLUTION = "#6a1b9a"  # a resolution's line, inserted or rewriting one of the paper's
# A list taller than this scrolls, the decision's line brought into view by the browser itself: an image
# that cannot load runs its onerror, the only script a panel's HTML may carry (a constant, never data).
HEIGHT_PX = 330
_SCROLL = (
    '<img alt="" src="data:,{n}" style="display:none" onerror="var b=this.parentElement,'
    "h=b.querySelector('[data-hit]');if(h)b.scrollTop=h.offsetTop-b.offsetTop-60\">"
)


_made: dict[tuple[str, tuple[int, str] | None], str] = {}  # (algorithm, decision) → its block, made once


def paper_html_for(algorithm: object, decision: tuple[int, str] | None, name: str) -> str:
    """:func:`paper_html` of an algorithm (by its registry name, which names one pseudocode): made once
    per decision, however many pages show it in however many frames."""
    key = (name, decision)
    made = _made.get(key)
    if made is None:
        if len(_made) >= 4096:
            _made.clear()
        made = _made[key] = paper_html(pseudocode_of(algorithm), decision, name)  # type: ignore[arg-type]
    return made


def paper_html(paper: Pseudocode | None, decision: tuple[int, str] | None, algorithm: str) -> str:
    """The block (algorithm) of the decision's line, or the first; ``decision``: (robot, rule id)."""
    if paper is None:
        return f"<i>{html.escape(algorithm)} gives no pseudocode.</i>"
    keys = paper.lines_of(decision[1]) if decision else ()
    within = {k for key in keys for k in paper.enclosing(key)}
    shown = next((found[0] for key in keys if (found := paper.line(key))), paper.blocks[0])
    if decision is None:
        head = "No robot has computed yet: its line will be highlighted here."
    elif not keys:
        reason = paper.outside.get(decision[1].split("/")[-1], "")
        head = f"Robot {decision[0]}: <code>{html.escape(decision[1])}</code> has no line in the paper" + (
            f": {html.escape(reason)}" if reason else ""
        )
    else:
        head = f"Robot {decision[0]}: <code>{html.escape(decision[1])}</code>, highlighted below"
    body = "".join(_line(line, line.key in keys, line.key in within) for line in shown.lines)
    scroll = _SCROLL.format(n=abs(hash((decision, shown.title))) % 10**8)
    return (
        f'<div style="font-size:0.85em">{head}<div style="margin:4px 0"><b>{html.escape(shown.title)}</b>'
        f"{_others(paper, shown)}</div>"
        f'<div style="max-height:{HEIGHT_PX}px;overflow:auto;font-family:monospace;font-size:0.92em;'
        f'line-height:1.35;border:1px solid #ddd;padding:2px 4px">{body}{scroll}</div></div>'
    )


def _others(paper: Pseudocode, shown: CodeBlock) -> str:
    rest = [b.title.split(":")[0] for b in paper.blocks if b is not shown]
    return f' <span style="color:#777">(the paper has also {", ".join(rest)})</span>' if rest else ""


def _line(line: CodeLine, hit: bool, within: bool) -> str:
    """One line: its number, its indentation, the text with the paper's symbols typeset."""
    text = symbol_html(line.text)
    indent = f"padding-left:{1.1 * max(line.depth - 1, 0):.1f}em"
    if not line.number and not line.resolution:  # a procedure's header
        return f'<div style="margin-top:3px"><b>{text}</b></div>'
    style = [indent, "flex:1"]
    if hit:
        style.append(f"background:{HIT};font-weight:bold")
    elif within:
        style.append(f"background:{WITHIN}")
    if line.replaced:
        style.append("text-decoration:line-through;color:#999")
    number = f'<span style="color:#999;display:inline-block;width:1.8em">{line.number}</span>'
    if line.resolution:
        number = f'<span style="color:{RESOLUTION};display:inline-block;width:1.8em">+</span>'
        tag = f'<span style="color:{RESOLUTION};font-size:0.85em"> [{html.escape(line.resolution)}]</span>'
        why = (
            f'<div style="color:{RESOLUTION};font-size:0.8em;font-style:italic">{symbol_html(line.why)}</div>'
        )
        text = f'<span style="color:{RESOLUTION}">{text}</span>{tag}{why}'
    marker = " data-hit" if hit else ""
    styled = ";".join(style)
    return f'<div{marker} style="display:flex"><div>{number}</div><div style="{styled}">{text}</div></div>'
