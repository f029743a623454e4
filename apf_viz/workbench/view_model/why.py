"""Why: the selected robot's last decision, explained from the snapshot it was computed on (the
evidence is the evidence), its regions placed in the global frame where the robot stood at that Look,
what has changed since (the one notion of staleness,
:mod:`~apf_viz.workbench.view_model.staleness`) and what it would decide now; and the same in words for
the panel."""

from __future__ import annotations

import html

from apf_viz.core.engine import Engine
from apf_viz.core.engine_state import Phase
from apf_viz.core.frames import move_to_global
from apf_viz.core.grid import Point
from apf_viz.core.portrayal import Band, Cells, Frame, HalfPlane, Line, Mark, explain, in_frame
from apf_viz.workbench.palette import region_color
from apf_viz.workbench.view_model.legend import symbol_html
from apf_viz.workbench.view_model.staleness import changes
from apf_viz.workbench.view_model.views import WhyView


def why_view(e: Engine, r: int, pts: list[Point]) -> WhyView:
    """Robot r's last decision and its evidence, in the global frame."""
    st = e.state
    view = st.decided[r]
    holds = st.phase[r] == Phase.LOOKED
    if view is None:
        return WhyView(r, None, pts[r], (), holds)
    explained = explain(e.algorithm, view, e.pattern)
    up = e.y_up[r]
    x, y = pts[r]
    if st.phase[r] != Phase.COMPUTED and explained.decision.move is not None:
        dx, dy = move_to_global(explained.decision.move, up).delta  # it has moved since that Look
        x, y = x - dx, y - dy
    regions = tuple(_to_global(m, (x, y), up) for m in explained.regions)
    now = e.decide(e.look(r))  # what it would decide on the present view
    changed = changes(e, r, "decided", pts)
    return WhyView(
        r,
        explained,
        (x, y),
        regions,
        holds,
        tuple(s.describe() for s in changed),
        now,
        tuple(s.robot for s in changed),
    )


_MATH = set("∅=≠∩∖∪⊂")
# How a phrase that describes a test's true case reads when the test came out false: the first rule
# whose pattern starts (or, for " … ", occurs in) the phrase rewrites it; otherwise "not so: …".
_NEGATIONS: tuple[tuple[str, str], ...] = (
    ("r on ", "r not on "),
    ("r in ", "r not in "),
    ("r is ", "r is not "),
    ("r leftmost", "r not leftmost"),
    ("two ", "not two "),
    ("another robot", "no other robot"),
    ("the other ", "no other "),
    ("another ", "no other "),
    ("a robot", "no robot"),
    ("no robot", "a robot"),
    ("no ", "a "),
    ("an ", "no "),
    ("a ", "no "),
    ("I am ", "I am not "),
    ("I can ", "I cannot "),
    ("I see ", "I do not see "),
    ("every ", "not every "),
    ("all ", "not all "),
    (" is not ", " is "),
    (" is ", " is not "),
    (" has ", " has not "),
    (" holds ", " does not hold "),
    (" shows ", " does not show "),
    (" answered", " has not answered"),
    (" reads ", " does not read "),
    (" moved ", " has not moved "),
)


def negated(phrase: str) -> str:
    """The phrase of a test's true case, read for its false case: "another robot on my row" → "no other
    robot on my row", "I am on K" → "I am not on K"."""
    if phrase.startswith("a robot ") and " is not " in phrase:  # not "no robot … is not done"
        return "every robot " + phrase[len("a robot ") :].replace(" is not ", " is ", 1)
    for pattern, replacement in _NEGATIONS:
        if pattern.startswith(" "):
            if pattern in phrase:
                return phrase.replace(pattern, replacement, 1)
        elif phrase.startswith(pattern):
            return replacement + phrase[len(pattern) :]
    return f"not so: {phrase}"


def found_row(symbol: str, value: object, meaning: str) -> tuple[str, str]:
    """One predicate as (what the robot found, the paper's test): a statement that holds, read
    positively, beside the paper's symbol and its value. A test written in symbols ("H_B^C(r) ∖ {r} ≠
    ∅") is read through its meaning; one written in words is itself the statement."""
    if not isinstance(value, bool):
        return f"{symbol_html(symbol)}: <b>{html.escape(str(value))}</b>", symbol_html(meaning)
    mathy = bool(_MATH & set(symbol))
    words = meaning if mathy else symbol
    found = words if value else negated(words)
    test = f"{symbol_html(symbol)} is {'true' if value else 'false'}" if mathy else symbol_html(meaning)
    if not mathy and not value:
        test = f'<span style="color:#666">(had it held: {symbol_html(meaning)})</span>' if meaning else ""
    return f"✔ {symbol_html(found)}", test


def why_markdown(why: WhyView | None) -> str:
    """The selected robot's last decision: rule id and text, then each predicate with its value."""
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
            "<tr><td>{}</td><td>{}</td></tr>".format(*found_row(p.symbol, p.value, p.meaning))
            for p in why.explanation.predicates
        )
        lines.append(
            '<table style="font-size:0.9em"><tr><th>what it found, in order</th><th>the test</th></tr>'
            f"{rows}</table>"
        )
    elif not d.rule_id:
        lines.append("_This algorithm does not explain its decisions._")
    else:
        lines.append("_No predicates are listed for this rule._")
    if why.regions:
        listed = " ".join(
            f'<span style="white-space:nowrap"><span style="display:inline-block;width:11px;height:11px;'
            f'background:rgb{region_color(i)};opacity:0.75"></span> {i + 1} {symbol_html(m.label)}</span>'
            for i, m in enumerate(why.regions)
        )
        lines.append(
            f"Regions it tested, shaded and numbered on the grid in the same colours: {listed}. They are in "
            "its own frame, where it stood when it looked (they stay there when it moves)."
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


def _to_global(mark: Mark, origin: Point, y_up: bool) -> Mark:
    """A mark in a robot's own frame (the robot at (0, 0), its own +y up) in the global frame."""
    ox, oy = origin
    s = 1 if y_up else -1
    if isinstance(mark, Line):
        return Line(mark.axis, ox + mark.at if mark.axis == "x" else oy + s * mark.at, mark.label)
    if isinstance(mark, Band):
        if mark.axis == "x":
            return Band("x", ox + mark.lo, ox + mark.hi, mark.label)
        lo, hi = sorted((oy + s * mark.lo, oy + s * mark.hi))
        return Band("y", lo, hi, mark.label)
    if isinstance(mark, HalfPlane):
        if mark.axis == "x":
            return HalfPlane("x", ox + mark.at, mark.side, mark.closed, mark.label)
        return HalfPlane("y", oy + s * mark.at, mark.side * s, mark.closed, mark.label)  # type: ignore[arg-type]
    if isinstance(mark, Frame):
        return Frame((ox + mark.origin[0], oy + s * mark.origin[1]), mark.y_sign * s, mark.label)
    return Cells(in_frame(mark.points, origin, y_up), mark.label, mark.style)
