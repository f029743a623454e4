"""What the algorithm's common waits depend on: the :class:`~apf_viz.core.algorithm.Watch` of a
"same light, stay" decision, so the engine asks a waiting robot again only when that changes.

Each builder below is a promise, argued in its docstring: on any later view that agrees with this one
inside the watch's regions and shows no new robot with a watched light, :func:`dispatch` answers
"same light, stay" again (perhaps by another rule). ``tests/test_watches.py`` checks the promise after
every step of many runs against a decision on the view computed from scratch. A wait not listed here has
no watch (None): the engine asks again after any change of the robot's view.

The regions are the robot's own: segments to a *witness* (a robot whose presence decided the wait) and
boxes bounded by vertical lines (L_I, L_V). Where several robots could witness, one whose segment
holds the fewest lattice points is taken (gcd(|dx|, |dy|) + 1 of them: a move can only touch a segment
on one of those; a single point, the witness itself, is best), and where any of several witnesses
would do, up to :data:`WITNESSES` are watched (``any_of``).
"""

from __future__ import annotations

from collections.abc import Iterable
from math import gcd

from apf_viz.algorithms.apf_opaque_grid.predicates import left_neighbour_line
from apf_viz.core.algorithm import Box, Watch
from apf_viz.core.view import Seen, Snapshot

PHASE1_LIGHTS = frozenset({"off", "terminal1"})
LATER_LIGHTS = frozenset({"symmetric", "decider", "call", "leader1", "leader", "done"})
PHASES_2_3 = frozenset({"decider", "leader", "done"})  # the lights that take an off robot out of Phase 1
_LEADER = frozenset({"leader"})
ROW_LEFT: Box = (None, -1, 0, 0)  # r's row, to its left
LEFT_HALF: Box = (None, -1, None, None)  # H_L^O(r): everything to r's left
WITNESSES = 8  # a fact that any of several robots shows is watched through this many of them


def _offset(s: Seen) -> tuple[int, int]:
    return (s.dx, s.dy)


def _sparsity(s: Seen, sign: int = 1) -> tuple[int, bool, int]:
    return (gcd(s.dx, s.dy), s.light != "done", sign * (abs(s.dx) + abs(s.dy)))


def sparsest(candidates: Iterable[Seen]) -> Seen:
    """A witness whose segment a move is least likely to touch (see the module's docstring): a done robot
    whose segment is a single point, else the nearest such robot, else the one with the fewest points.
    One pass without sorting: a large view has hundreds of candidates."""
    candidates = list(candidates)
    best, nearest = None, 0
    for s in candidates:
        if gcd(s.dx, s.dy) == 1:
            if s.light == "done":
                return s
            d = abs(s.dx) + abs(s.dy)
            if best is None or d < nearest:
                best, nearest = s, d
    return best if best is not None else min(candidates, key=_sparsity)


def some_witnesses(candidates: Iterable[Seen], far: bool = False) -> tuple[tuple[int, int], ...]:
    """Up to :data:`WITNESSES` of the candidates, sparsest first: any one of them suffices (``any_of``).
    The candidates are read only as far as needed (a view's lazy range, :meth:`Snapshot.iter_between`)."""
    if far:
        taken = list(candidates)
    else:  # the usual case, cheaply: the first witnesses whose segment is a single point
        taken, single = [], []
        for s in candidates:
            taken.append(s)
            if gcd(s.dx, s.dy) == 1:
                single.append(s)
                if len(single) == WITNESSES:
                    return tuple(map(_offset, single))
    sign = -1 if far else 1
    chosen = sorted(taken, key=lambda s: _sparsity(s, sign))[:WITNESSES]
    return tuple(map(_offset, chosen))


def _to_my_line_from_left_line(view: Snapshot) -> Box:
    """The columns from L_I(r) (or, with none, everything to the left) to r's own: L_I, L_V and the
    empty columns between, i.e. everything that decides L_I, L_V and H_L^O."""
    l_i = left_neighbour_line(view)
    return (l_i[0].dx if l_i else None, 0, None, None)


def phase1_wait(view: Snapshot) -> Watch:
    """A1.off.wait under G1: r is off and sees only off/terminal1 robots. A robot of a later light coming
    into sight changes nothing unless it is a leader or done robot (Phase 3 would apply) or a decider
    (two on L_I start Phase 2): any other makes G1 true, and r waits (G1-wait). So with no leader, done
    or decider robot coming into sight, Algorithm 1's off rules decide, and they read only L_V, H_L^O
    and L_I (their lights and K), all inside the box from L_I to L_V; "no leader1 on R_I" only matters
    while G1 is false, i.e. while no leader1 is in sight.

    Tighter when r sees no terminal1 robot and some robot w to its left: with w in sight there (any of
    several, wherever they move in the left half) H_L^O is not empty, so the terminal rule cannot fire,
    and with no terminal1 robot coming into sight L_I cannot hold two; nothing else is read."""
    left = view.column_start(0)
    if left and "terminal1" not in view.lights():
        witnesses = some_witnesses(view.iter_between(0, left))
        return Watch(any_of=witnesses, within=LEFT_HALF, lights=PHASES_2_3 | {"terminal1"})
    return Watch(boxes=(_to_my_line_from_left_line(view),), lights=PHASES_2_3)


def g1_wait(view: Snapshot) -> Watch:
    """A1.off.G1-wait: r is off, sees no leader/done robot, no two deciders on L_I, and a robot w of a later
    light. With w in sight with its light (any of several, wherever they move: a walking leader1 may be
    one) G1 holds; with no leader/done coming into sight Phase 3 does not apply; and two deciders on L_I
    cannot appear: either no decider is in sight and none comes into sight, or L_I is kept (a box)."""
    later = some_witnesses(s for s in view.robots if s.light not in PHASE1_LIGHTS)
    if any(s.light == "decider" for s in view.robots):
        return Watch(boxes=(_to_my_line_from_left_line(view),), any_of=later, lights=_LEADER | {"done"})
    return Watch(any_of=later, lights=frozenset({"leader", "done", "decider"}))


def no_leader(view: Snapshot) -> Watch:
    """A3.off.no-leader: r is off, sees a done robot d and no leader. With d kept Phase 3 still applies;
    with no leader coming into sight Algorithm 3 still finds none."""
    d = sparsest(s for s in view.robots if s.light == "done")
    return Watch(segments=(_offset(d),), lights=_LEADER)


def not_my_turn(view: Snapshot, leader: Seen, between: Box | None) -> Watch | None:
    """A3.off.not-my-turn: r is off above the line and sees one leader; ``between`` is the box of the rows
    strictly between r's row and the leader's (None when r's row is next to it). A robot of a watched
    light coming into sight, or a watched region touched, asks again.

    While the leader stays in sight at the same offset (and no second one comes into sight) the frame is
    the same, and it stays not r's turn while a robot stands on r's row to its left or between the rows
    (``occupied``: whoever it is, and however it moves about there, as the traveller does). A robot there
    is visible or hidden behind another one there: a segment from r into either box runs inside it. The
    leader need not be watched when a robot w to r's left stays in sight there (any of several, followed
    wherever they move in the left half: a traveller may be one) and no terminal1, decider or leader
    robot comes into sight (except this leader at its offset, ``seen_at``: seen there again, the view
    agrees with this one). If the leader is hidden, r either sees a done robot (Phase 3 without a
    leader: wait) or runs Phases 1–2, where no decider means no Phase 2, G1 at most waits, and
    Algorithm 1's off rules need H_L^O empty (w is there) or two terminal1 robots on L_I (none in
    sight). With two leaders in sight the first in the view's order is taken: no watch."""
    if view.count("leader") != 1:
        return None
    occupied = (ROW_LEFT, between) if between is not None else (ROW_LEFT,)
    left = view.column_start(0)
    lights = view.lights()
    if left and "terminal1" not in lights and "decider" not in lights:
        # Any robot but the leader; only if the leader is all there is to the left, the leader.
        witnesses = some_witnesses(s for s in view.iter_between(0, left) if s.light != "leader")
        return Watch(
            any_of=witnesses or some_witnesses(view.iter_between(0, left)),
            within=LEFT_HALF,
            occupied=occupied,
            lights=frozenset({"leader", "terminal1", "decider"}),
            seen_at=(_offset(leader),),
        )
    return Watch(segments=(_offset(leader),), occupied=occupied, lights=_LEADER)


def line_waits(view: Snapshot, side: int, waiting: list[Seen]) -> Watch | None:
    """A3.off.line-wait: r is on the leader's row (the line), sees the leader there, and ``waiting`` are the
    robots on the frame's upper side (local ``side``·dy > 0) still forming. The side is read off the
    first robot off r's row in the view's order; when no robot stands on the other side, any robot off
    the row gives the same side. So with the box of r's row and the other side kept (it holds the
    leader: the frame's origin), no second leader coming into sight (the first in the view's order is
    taken), and any one of the waiting robots still in sight on the upper side with its light (wherever
    it walks there: ``within``), r still waits. The traveller walking above the line touches none of
    this; it enters the box once, when it joins the line. With a robot on the other side (not a leader
    configuration) there is no watch."""
    if any(side * s.dy < 0 for s in view.robots):
        return None
    other_side: Box = (None, None, None, 0) if side == 1 else (None, None, 0, None)
    upper_side: Box = (None, None, 1, None) if side == 1 else (None, None, None, -1)
    return Watch(
        boxes=(other_side,), any_of=some_witnesses(waiting, far=True), within=upper_side, lights=_LEADER
    )


def leader_waits(pending: list[Seen]) -> Watch:
    """A3.leader.wait: the leader sees robots still forming. With any one of them still in sight with its
    light, wherever it has moved, the leader still waits. Among equals the farthest first: the robots
    leave the crowd nearest the line first."""
    return Watch(any_of=some_witnesses(pending, far=True))
