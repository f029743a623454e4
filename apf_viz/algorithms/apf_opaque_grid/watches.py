"""What the algorithm's common waits depend on: the :class:`~apf_viz.core.algorithm.Watch` of a
"same light, stay" decision, so the engine asks a waiting robot again only when that changes.

Each builder below is a promise, argued in its docstring: on any later view that agrees with this one
inside the watch's regions and shows no new robot with a watched light, :func:`dispatch` answers
"same light, stay" again (perhaps by another rule). ``tests/test_watches.py`` checks the promise after
every step of many runs against a decision on the view computed from scratch. A wait not listed here has
no watch (None): the engine asks again after any change of the robot's view.

The regions are the robot's own: segments to a *witness* (a robot whose presence decided the wait) and
boxes bounded by vertical lines (L_I, L_V). Where several robots could witness, the one whose segment
holds the fewest lattice points is taken (gcd(|dx|, |dy|) + 1 of them: a move can only touch a segment
on one of those), then a ``done`` one (it never moves or changes light again).
"""

from __future__ import annotations

from bisect import bisect_left
from collections.abc import Iterable
from math import gcd

from apf_viz.algorithms.apf_opaque_grid.predicates import left_neighbour_line
from apf_viz.core.algorithm import Box, Watch
from apf_viz.core.view import Seen, Snapshot

PHASE1_LIGHTS = frozenset({"off", "terminal1"})
LATER_LIGHTS = frozenset({"symmetric", "decider", "call", "leader1", "leader", "done"})
_LEADER = frozenset({"leader"})


def _offset(s: Seen) -> tuple[int, int]:
    return (s.dx, s.dy)


def sparsest(candidates: Iterable[Seen], far: bool = False) -> Seen:
    """The witness whose segment a move is least likely to touch (see the module's docstring); among
    equals the nearest, or with ``far`` the farthest."""
    sign = -1 if far else 1
    return min(candidates, key=lambda s: (gcd(s.dx, s.dy), s.light != "done", sign * (abs(s.dx) + abs(s.dy))))


def _to_my_line_from_left_line(view: Snapshot) -> Box:
    """The columns from L_I(r) (or, with none, everything to the left) to r's own: L_I, L_V and the
    empty columns between, i.e. everything that decides L_I, L_V and H_L^O."""
    l_i = left_neighbour_line(view)
    return (l_i[0].dx if l_i else None, 0, None, None)


def phase1_wait(view: Snapshot) -> Watch:
    """A1.off.wait under G1: r is off and sees only off/terminal1 robots. While no robot of a later light
    comes into sight, G1 stays false, no leader/done or decider is seen (so neither Phase 3 nor Phase 2
    applies), and "no leader1 on R_I" holds; the rest of Algorithm 1's off rules read only L_V, H_L^O and
    L_I (their lights and K), all inside the box from L_I to L_V.

    Tighter when r sees no terminal1 robot and some robot w to its left: with w kept H_L^O is not empty,
    so the terminal rule cannot fire, and with no terminal1 robot coming into sight L_I cannot hold two;
    nothing else is read."""
    left = view.robots[: bisect_left(view.robots, (0,))]
    if left and not any(s.light == "terminal1" for s in view.robots):
        return Watch(segments=(_offset(sparsest(left)),), lights=LATER_LIGHTS | {"terminal1"})
    return Watch(boxes=(_to_my_line_from_left_line(view),), lights=LATER_LIGHTS)


def g1_wait(view: Snapshot) -> Watch:
    """A1.off.G1-wait: r is off, sees no leader/done robot, no two deciders on L_I, and a robot w of a later
    light. With w kept (a segment) G1 holds; with no leader/done coming into sight Phase 3 does not
    apply; and two deciders on L_I cannot appear: either no decider is in sight and none comes into
    sight, or L_I is kept (a box)."""
    w = sparsest(s for s in view.robots if s.light not in PHASE1_LIGHTS)
    if any(s.light == "decider" for s in view.robots):
        return Watch(
            boxes=(_to_my_line_from_left_line(view),), segments=(_offset(w),), lights=_LEADER | {"done"}
        )
    return Watch(segments=(_offset(w),), lights=frozenset({"leader", "done", "decider"}))


def no_leader(view: Snapshot) -> Watch:
    """A3.off.no-leader: r is off, sees a done robot d and no leader. With d kept Phase 3 still applies;
    with no leader coming into sight Algorithm 3 still finds none."""
    d = sparsest(s for s in view.robots if s.light == "done")
    return Watch(segments=(_offset(d),), lights=_LEADER)


def not_my_turn(view: Snapshot, leader: Seen, witness: Seen) -> Watch | None:
    """A3.off.not-my-turn: r is off above the line and sees one leader; ``witness`` is the robot on r's
    row to its left, or one strictly between r's row and the leader's. With the leader kept (and no
    second one coming into sight) the leader's frame is the same (it depends on the leader's offset
    alone off its row); with the witness kept r is still not the leftmost of its row, or a robot is still
    between. With two leaders in sight the first in the view's order is taken: no watch."""
    if sum(1 for s in view.robots if s.light == "leader") != 1:
        return None
    return Watch(segments=(_offset(leader), _offset(witness)), lights=_LEADER)


def leader_waits(pending: list[Seen]) -> Watch:
    """A3.leader.wait: the leader sees a robot still forming. With that robot kept (its light too) the
    leader still waits. Among equals the farthest: the robots leave the crowd nearest the line first."""
    return Watch(segments=(_offset(sparsest(pending, far=True)),))
