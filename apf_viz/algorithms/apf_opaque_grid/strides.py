"""How far a decision repeats: the ``stride`` of the walks of Algorithms 2 and 3.

A stride is a promise (:class:`~apf_viz.core.algorithm.Decision`): after the robot's own next j moves
(1 ≤ j < stride), with the same robots in sight and nothing else moved, it decides exactly the same. The
rules themselves give the distance to their next branch (LineMove and TargetMove: to the next corner of
the path); the cuts below stop a stride where a robot the rule reads would change its place relative to
the walker: a row or column it passes. ``tests/test_fast_forward.py`` checks every promise made in many
runs against decisions on the shifted views.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from apf_viz.core.algorithm import Decision
from apf_viz.core.view import Seen, Snapshot

FOREVER = 1 << 62
"""The stride of a decision that no move of the robot's own can change (the engine cuts it to what it
can check)."""


def _cut(decision: Decision, stride: int) -> Decision:
    return replace(decision, stride=max(1, min(decision.stride, stride)))


def clear_rows_stride(decision: Decision, view: Snapshot, side: int) -> Decision:
    """Cut the stride of a move up (away from the line, frame +y; ``side``: the frame's +y in the robot's
    own frame) to the rows no visible robot stands on: a robot on the robot's own row or on a row it
    passes would, once the robot is above it, stand between it and the line, and the robot would wait
    (Algorithm 3 line 5)."""
    if decision.stride < 2 or decision.move is None or decision.move.delta[1] != side:
        return decision
    up = side * view.columns.dy
    above = up[up >= 0]
    if above.size:
        return _cut(decision, int(above.min()))
    return decision


def fixed_sign_stride(decision: Decision, anchors: list[Seen]) -> Decision:
    """Cut the stride of a vertical move to the rows where no anchor robot comes onto the robot's own
    row: the leader reads its frame's +y off the first anchor off its row (:func:`_up_towards`)."""
    my = decision.move.delta[1] if decision.move is not None else 0
    if decision.stride < 2 or not my:
        return decision
    reach = [abs(d.dy) for d in anchors if d.dy * my >= 0]  # on my row now, or a row ahead of me
    if reach:
        return _cut(decision, min(reach))
    return decision


def vertical_stride(decision: Decision, view: Snapshot) -> Decision:
    """A vertical walk repeats until a visible robot's row: until then every robot stays above or below
    the walker (the extreme-row tests, SD's sides of R_I), and the columns (L_I, L_V, R_I) do not change.
    A robot on the walker's own row changes side at once."""
    assert decision.move is not None  # a walk's stride: the decision moves
    dy = view.columns.dy
    my = decision.move.delta[1]
    ahead = np.abs(dy[dy * my >= 0])
    return _cut(decision, int(ahead.min()) if ahead.size else 1)


def left_walk_stride(decision: Decision, view: Snapshot) -> Decision:
    """A walk left repeats until the nearest column to the left (L_I) when the walker is alone on its
    column: every column it passes is empty, so L_I, R_I and the rows stay as they are. With another robot
    on its column, that column becomes R_I at the first move."""
    dx = view.columns.dx
    if (dx == 0).any():
        return _cut(decision, 1)
    left = dx[dx < 0]
    return _cut(decision, int(-left.max()) if left.size else 1)
