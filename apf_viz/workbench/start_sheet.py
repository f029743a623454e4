"""A lecture author's reference, printed without serving anything (``apf-viz lecture show`` and ``apf-viz
lecture rules``): a start with its robots' numbers, positions, y-axes and lights and its mirror axis, as a
stop's ``select``, ``expect`` and words refer to them; and every rule id an algorithm's decisions carry."""

from __future__ import annotations

from fractions import Fraction

from apf_viz.core.algorithm import Algorithm
from apf_viz.core.grid import Point
from apf_viz.core.portrayal import rules_of
from apf_viz.core.symmetry import describe_axis, mirror_axis
from apf_viz.workbench.session import Session

PICTURE_MAX = 40
"""A start at most this many cells wide and tall is drawn as text too (a larger one is only listed)."""


def start_sheet(session: Session, title: str) -> str:
    """The run the session stands at, from its start: each robot's number, cell, y-axis and light, the
    mirror axis, and (for a small start) a picture of the numbers on the grid."""
    e = session.engine
    view = session.view()
    lines = [f"{title}: {e.k} robots, a pattern of {len(e.pattern)} cells, {e.algorithm.name}"]
    for i, (robot, y_up) in enumerate(zip(view.robots, e.y_up, strict=True)):
        lines.append(
            f"  robot {i:>3} at {robot.position}, +y {'up  ' if y_up else 'down'}, light {robot.light}"
        )
    lines.append(_axis_words([r.position for r in view.robots]))
    lines.extend(_picture([r.position for r in view.robots]))
    return "\n".join(lines)


def _axis_words(points: list[Point]) -> str:
    c = mirror_axis(points)
    if c is None:
        return "mirror axis: none (the robots are not mirror-symmetric about a horizontal line)"
    on = [i for i, (_, y) in enumerate(points) if Fraction(y) == c]
    if on:
        robots = f"robot {on[0]}" if len(on) == 1 else f"robots {', '.join(map(str, on))}"
        return f"mirror axis: {describe_axis(c)}, through {robots} (the paper's K)"
    return f"mirror axis: {describe_axis(c)}, through no robot: unsolvable (Theorem 1)"


def _picture(points: list[Point]) -> list[str]:
    """The robots' numbers where they stand, the top row first, with the grid's coordinates."""
    xs, ys = [x for x, _ in points], [y for _, y in points]
    x0, x1, y0, y1 = min(xs), max(xs), min(ys), max(ys)
    if x1 - x0 >= PICTURE_MAX or y1 - y0 >= PICTURE_MAX:
        return [f"(no picture: the start spans more than {PICTURE_MAX} cells)"]
    at = {p: i for i, p in enumerate(points)}
    width = max(3, len(str(len(points) - 1)) + 1, len(str(x0)) + 1, len(str(x1)) + 1)
    rows = []
    for y in range(y1, y0 - 1, -1):
        cells = "".join(f"{at.get((x, y), '·'):>{width}}" for x in range(x0, x1 + 1))
        rows.append(f"{y:>5} |{cells}")
    rows.append("      +" + "-" * (width * (x1 - x0 + 1)))
    rows.append("       " + "".join(f"{x:>{width}}" for x in range(x0, x1 + 1)))
    return rows


def rules_sheet(algorithm: Algorithm) -> str:
    """Every rule id the algorithm's decisions carry (a stop's ``until: {"rule": …}``), with its words."""
    rules = rules_of(algorithm)
    if not rules:
        return f"{algorithm.name} lists no rule ids"
    width = max(map(len, rules))
    return "\n".join(
        [f"{algorithm.name}: {len(rules)} rule ids"] + [f"  {r:<{width}}  {w}" for r, w in rules.items()]
    )
