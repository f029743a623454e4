"""Algorithm 3, *Pattern Formation from Leader Configuration*, with LineMove and TargetMove.

The leader r₀ fixes the coordinate system: r₀ is at (0, −1) and +y points into the open half that holds
the other robots. The followers first form a compact line (1, −1) … (n−1, −1) on L_H(r₀), then leave it one
by one, left end first, for targets t_0 … t_{n−1}; the leader fills t_{n−1} last.

Embedding of the drawn pattern (the paper leaves it open, B16): translate it so that min y = 1 and
min x = 0. Row 0 (L_H1) stays free for travelling robots, row −1 holds the line, and every target is above
both, so no path of LineMove or TargetMove crosses a placed robot. Targets are ordered top row first,
right to left within a row, so t_{n−1} is the bottom-left target and each robot travels below every
robot already done.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import lru_cache
from operator import itemgetter

import numpy as np

from apf_viz.algorithms.apf_opaque_grid import watches
from apf_viz.algorithms.apf_opaque_grid.phase1 import stay
from apf_viz.algorithms.apf_opaque_grid.resolutions import G4, LA, N2, P3, Resolutions, deviation
from apf_viz.algorithms.apf_opaque_grid.strides import FOREVER, clear_rows_stride, fixed_sign_stride
from apf_viz.core.algorithm import Box, Decision, Pattern
from apf_viz.core.grid import Direction, Point
from apf_viz.core.portrayal import NO_EVIDENCE, Band, Evidence, Frame, Line
from apf_viz.core.view import Seen, Snapshot

LEADER1 = frozenset({"leader1"})
"""G4's light: a robot showing it may hold a move of Phase 2 computed before the leader was elected."""


def embedded_targets(pattern: Pattern) -> tuple[Point, ...]:
    """t_0 … t_{n−1}: the pattern translated to min x = 0, min y = 1, sorted by (−y, −x)."""
    # Every Compute asks for the same pattern object: an identity check spares hashing k points.
    global _last_embedded
    last = _last_embedded  # one tuple, read once: safe while another thread replaces it
    if last[0] is pattern:
        return last[1]
    targets = _embedded_targets(pattern)
    _last_embedded = (pattern, targets)
    return targets


_last_embedded: tuple[Pattern | None, tuple[Point, ...]] = (None, ())


@lru_cache(maxsize=64)
def _embedded_targets(pattern: Pattern) -> tuple[Point, ...]:
    mx = min(x for x, _ in pattern)
    my = min(y for _, y in pattern)
    placed = [(x - mx, y - my + 1) for x, y in pattern]
    return tuple(sorted(placed, key=lambda p: (-p[1], -p[0])))


@dataclass(frozen=True)
class LeaderFrame:
    """The coordinate system agreed through the leader: a robot's local offsets mapped to it.

    ``origin`` is the local offset of the frame's (0, 0); ``s`` is +1 if the local +y is the frame's +y."""

    origin: Point
    s: int

    def of(self, robot: Seen) -> Point:
        return (robot.dx - self.origin[0], self.s * (robot.dy - self.origin[1]))

    @property
    def me(self) -> Point:
        return (-self.origin[0], -self.s * self.origin[1])

    def local_move(self, fx: int, fy: int) -> Direction:
        return Direction.from_delta(fx, self.s * fy)


def follower_frame(view: Snapshot, leader: Seen) -> LeaderFrame:
    """The frame of a robot that sees the leader at local (lx, ly): r₀ ↦ (0, −1), +y away from r₀'s row
    towards the other robots. On r₀'s own row the side is read off the first visible robot (in the
    view's order) off that row; with none (the line is complete) the robot takes its own +y: the pattern
    may then form mirrored."""
    lx, ly = leader.dx, leader.dy
    if ly != 0:
        s = 1 if ly < 0 else -1
    else:
        dy = view.columns.dy
        off_row = (dy != ly).nonzero()[0]
        s = (1 if dy[off_row[0]] > ly else -1) if off_row.size else 1
    # frame(p) = (p.dx − lx, s·(p.dy − ly) − 1) = (p.dx − ox, s·(p.dy − oy)) with oy = ly + s.
    return LeaderFrame((lx, ly + s), s)


def _step_towards(frame: LeaderFrame, me: Point, goal: Point, horizontal_first: bool) -> Direction:
    dx, dy = goal[0] - me[0], goal[1] - me[1]
    if horizontal_first and dx:
        return frame.local_move(1 if dx > 0 else -1, 0)
    if dy:
        return frame.local_move(0, 1 if dy > 0 else -1)
    return frame.local_move(1 if dx > 0 else -1, 0)


def line_move(frame: LeaderFrame, j: int, light: str) -> Decision:
    """LineMove(j): down to L_H1 (row 0), along it to (j, 0), then down into (j, −1).

    A stride (:class:`~apf_viz.core.algorithm.Decision`) counts the moves until the next branch: the
    rule, j and the frame do not depend on where the robot is on its way."""
    x, y = frame.me
    if y == 0:
        if x == j:
            return Decision(
                light,
                frame.local_move(0, -1),
                f"LineMove({j}): at ({j}, 0) → move to ({j}, −1)",
                "LineMove.into-line",
            )
        step = frame.local_move(1 if j > x else -1, 0)
        return Decision(
            light,
            step,
            f"LineMove({j}): on L_H1 → move horizontally towards ({j}, 0)",
            "LineMove.along",
            stride=abs(j - x),
        )
    return Decision(
        light,
        frame.local_move(0, -1),
        f"LineMove({j}): above L_H1 → move down towards L_H1",
        "LineMove.down",
        stride=y,
    )


def target_move(frame: LeaderFrame, j: int, target: Point, light: str, frame_fixed: bool = True) -> Decision:
    """TargetMove(j): up to L_{t_j−1} (the row below t_j), along it to below t_j, then up into t_j.

    The stride counts the moves until the next branch. With ``frame_fixed`` False the frame moves with
    the robot (the paper's leader frame puts it at (0, −1) wherever it is), so the same decision repeats
    forever."""
    x, y = frame.me
    tx, ty = target
    name = f"TargetMove({j}) to t_{j} = ({tx}, {ty})"
    if (x, y) == target:
        return Decision("done", None, f"{name}: at t_{j} → done", "TargetMove.done")
    if y == ty - 1:
        if x == tx:
            return Decision(
                light, frame.local_move(0, 1), f"{name}: below t_{j} → move up into it", "TargetMove.into"
            )
        step = frame.local_move(1 if tx > x else -1, 0)
        stride = abs(tx - x) if frame_fixed else FOREVER
        return Decision(
            light, step, f"{name}: on L_(t_j−1) → move horizontally", "TargetMove.along", stride=stride
        )
    step = frame.local_move(0, 1 if ty - 1 > y else -1)
    stride = _vertical_stride(x, y, target) if frame_fixed else FOREVER
    return Decision(
        light, step, f"{name}: move vertically towards L_(t_j−1)", "TargetMove.vertical", stride=stride
    )


def _vertical_stride(x: int, y: int, target: Point) -> int:
    """Moves of TargetMove's vertical branch until its next branch: the row below t_j (L_(t_j−1)), or
    t_j itself first for a robot coming down its own target's column (there it is done, not one row
    below)."""
    tx, ty = target
    if x == tx and y > ty:
        return y - ty
    return abs(ty - 1 - y)


_dy = itemgetter(1)
_light = itemgetter(2)


def leftmost_on_own_row(view: Snapshot, ev: Evidence = NO_EVIDENCE) -> bool:
    """r is leftmost on L_H(r): no visible robot on r's row to its left (exact: the nearest one there
    would be visible). The snapshot is sorted by dx, so the robots left of r are a prefix."""
    c = view.columns
    value = not (c.dy[: np.searchsorted(c.dx, 0)] == 0).any()
    if ev.active:
        ev.region(Line("y", 0, "L_H(r)"))
        ev.test("r leftmost on L_H(r)", value, "no robot on my row to my left")
    return value


def robots_between(view: Snapshot, frame: LeaderFrame, ev: Evidence = NO_EVIDENCE) -> bool:
    """H_B^O(r) ∩ H_U^O(r₀) ≠ ∅: a robot strictly between r's row and the leader's row (exact by V1: the
    strip is convex). In the leader frame that is −1 < y′ < y; in r's frame, y′ − y = s·dy."""
    box = _between_rows(frame)
    dy = view.columns.dy
    value = box is not None and bool(((box[2] <= dy) & (dy <= box[3])).any())
    if ev.active:
        if box is not None and box[2] is not None and box[3] is not None:  # rows bounded both ways
            ev.region(Band("y", box[2], box[3], "H_B^O(r) ∩ H_U^O(r₀)"))
        ev.test("H_B^O(r) ∩ H_U^O(r₀) ≠ ∅", value, "a robot strictly between my row and the leader's")
    return value


def _frame_region(ev: Evidence, frame: LeaderFrame) -> None:
    if ev.active:  # the traveller decides at each of its steps: no mark made to be thrown away
        ev.region(Frame(frame.origin, frame.s, "the leader's frame"))


def pattern_formation_off(
    view: Snapshot, pattern: Pattern, res: Resolutions, ev: Evidence = NO_EVIDENCE
) -> Decision:
    """Algorithm 3, r.light = off (lines 4–22), for a robot that sees the leader.

    It reads the view's arrays (:class:`~apf_viz.core.view.Columns`): the traveller decides on a view of
    hundreds of robots at each of its steps."""
    c = view.columns
    leaders = c.showing("leader").nonzero()[0]
    if not leaders.size:
        ev.test("the leader in sight", False, "I see the robot with light leader")
        return stay(
            view,
            "Phase 3 (off): the leader is not in sight → wait",
            "A3.off.no-leader",
            watches.no_leader(view),
        )
    ev.test("the leader in sight", True, "I see the robot with light leader")
    if G4 in res and deviation(ev, G4, bool(view.lights() & LEADER1)):
        # Algorithm 3 starts from a leader configuration: one leader, every other robot off. Lemma
        # P2:l5 allows a second leader1 (a decider and an off robot of R_I promoted in the same race);
        # under ASYNC it can miss the first (hidden, or gone from L_I) and hold a Phase-2 move computed
        # before the leader was elected. Until it sees the leader and turns off (G3), nobody moves.
        return stay(view, "Phase 3 (off): a leader1 is still in sight → wait (G4)", "A3.off.G4-wait")
    leader = c.seen(int(leaders[0]))  # the first in the view's order
    targets = embedded_targets(pattern)
    frame = follower_frame(view, leader)
    _frame_region(ev, frame)
    x, y = frame.me
    if ev.active:
        ev.test("my place in the leader's frame", f"({x}, {y})", "the line is row −1, L_H1 is row 0")
    if y > -1:
        return _off_above_the_line(view, res, ev, frame, leader, int(leaders[0]), targets)
    return _off_on_the_line(view, res, ev, frame, leader)


def _off_above_the_line(
    view: Snapshot,
    res: Resolutions,
    ev: Evidence,
    frame: LeaderFrame,
    leader: Seen,
    leader_at: int,
    targets: tuple[Point, ...],
) -> Decision:
    """Algorithm 3, r.light = off, above the line (y > −1 in the leader's frame): the robot whose turn it
    is joins the line (growing) or goes to its target (the line emptying)."""
    c = view.columns
    n = len(targets)
    # Line 5: the leader below (r₀ ∈ H_B^O(r) holds as y > −1), r leftmost on L_H(r), none between.
    leftmost = leftmost_on_own_row(view, ev)
    if leftmost and not robots_between(view, frame, ev):
        # Row −1 of the leader's frame is the leader's own row, and frame x is dx − the leader's dx.
        on_row = c.dy == leader.dy
        on_row[leader_at] = False
        line = c.dx[on_row] - leader.dx  # sorted: the view is sorted by dx
        i = int(line.size)
        ev.test("robots on the line", i, "robots I see on row −1 of the leader's frame")
        if i == 0:
            done_seen = bool(c.showing("done").any())
            ev.test("a done robot in sight", done_seen, "the line has already emptied into targets")
            if done_seen or (N2 in res and deviation(ev, N2, n == 2)):
                first = _to_target(
                    frame, n - 2, targets, "line empty, a done robot in sight", "A3.off.first-target"
                )
                return clear_rows_stride(first, view, frame.s)
            return _compose(line_move(frame, 1, "off"), "A3.off.start-line")
        growing = bool(line[0] == 1 and line[-1] == i)  # distinct and sorted: exactly 1..i
        if ev.test("the line is (1..i, −1)", growing, "the line is still growing"):
            return _compose(line_move(frame, i + 1, "off"), "A3.off.grow-line")
        emptying = bool(line[0] == n - i and line[-1] == n - 1)
        if ev.test(f"the line is ({n - i}..{n - 1}, −1)", emptying, "it is emptying"):
            following = _to_target(
                frame, n - i - 2, targets, f"{i} robots left on the line", "A3.off.next-target"
            )
            return clear_rows_stride(following, view, frame.s)
        return stay(
            view,
            "Phase 3 (off): the line is neither growing nor shrinking as expected → wait",
            "A3.off.line-unexpected",
        )
    return stay(
        view,
        "Phase 3 (off): not the leftmost of the lowest row above the line → wait",
        "A3.off.not-my-turn",
        watches.not_my_turn(view, leader, _between_rows(frame)),
    )


def _off_on_the_line(
    view: Snapshot, res: Resolutions, ev: Evidence, frame: LeaderFrame, leader: Seen
) -> Decision:
    """Algorithm 3, r.light = off, on the line (y = −1): its left end leaves for row 0 once no robot
    above is still on its way.

    The frame puts the leader's row at −1 and every other robot on or above it (follower_frame:
    y = |ly| − 1 ≥ 0 off the leader's row, −1 on it), so y < −1 cannot happen."""
    c = view.columns
    x = frame.me[0]
    p3 = P3 in res
    # Frame y > −1 is s·(dy − the leader's dy) ≥ 1 (frame y = s·(dy − ly) − 1): off the leader's row.
    side, ly = frame.s, leader.dy
    above = side * (c.dy - ly) > 0
    done, off = c.showing("done"), c.showing("off")
    forming = above & ~done if p3 else above & off  # the robots the line waits for
    waiting = bool(forming.any())
    if p3 and ev.active and (above & ~done & ~off).any():
        deviation(ev, P3, True)
    blockers = "not done" if p3 else "off"
    if not ev.test(f"a robot above the line is {blockers}", waiting, "a robot is still on its way"):
        return Decision(
            "off",
            frame.local_move(0, 1),
            f"Phase 3 (off): left end of the line at ({x}, −1) → move to ({x}, 0)",
            "A3.off.leave-line",
        )
    return stay(
        view,
        "Phase 3 (off): on the line, robots above are not done → wait",
        "A3.off.line-wait",
        watches.line_waits(view, side, [c.seen(i) for i in forming.nonzero()[0].tolist()]),
    )


def _between_rows(frame: LeaderFrame) -> Box | None:
    """H_B^O(r) ∩ H_U^O(r₀) as a box of r's frame (the rows :func:`robots_between` reads); None if empty."""
    y = frame.me[1]
    lo, hi = (-y, -1) if frame.s == 1 else (1, y)
    return (None, None, lo, hi) if lo <= hi else None


def _compose(decision: Decision, rule_id: str) -> Decision:
    return decision.named(decision.rule, f"{rule_id}/{decision.rule_id}")


def _to_target(frame: LeaderFrame, j: int, targets: tuple[Point, ...], why: str, rule_id: str) -> Decision:
    if not 0 <= j < len(targets):
        return Decision(
            "off",
            None,
            f"Phase 3 (off): {why}, but t_{j} does not exist → wait",
            f"{rule_id}/TargetMove.missing",
        )
    decision = target_move(frame, j, targets[j], "off")
    return decision.named(f"Phase 3 (off): {why} → {decision.rule}", f"{rule_id}/{decision.rule_id}")


def pattern_formation_leader(
    view: Snapshot, pattern: Pattern, res: Resolutions, ev: Evidence = NO_EVIDENCE
) -> Decision:
    """Algorithm 3, r.light = leader (lines 23–27): wait for the others, then fill t_{n−1}."""
    targets = embedded_targets(pattern)
    n = len(targets)
    p3 = P3 in res
    pending = [s for s in view.robots if (s.light != "done" if p3 else s.light == "off")]
    if p3 and ev.active and any(s.light not in ("off", "done") for s in view.robots):
        deviation(ev, P3, True)
    if ev.test("a robot still forming", bool(pending), "a robot I see is not done"):
        return stay(
            view,
            "Phase 3 (leader): robots are still forming → wait",
            "A3.leader.wait",
            watches.leader_waits(pending),
        )
    if ev.test("n = 1", n == 1, "the pattern is one point"):
        return Decision(
            "done", None, "Phase 3 (leader): alone, the pattern is one point → done", "A3.leader.alone"
        )
    done = [s for s in view.robots if s.light == "done"]
    if not ev.test("a done robot in sight", bool(done), "I can anchor my frame on the placed robots"):
        return stay(view, "Phase 3 (leader): no done robot in sight → wait", "A3.leader.no-done")
    s = _up_towards(done)
    # Without LA, the paper's frame: r₀ itself is always (0, −1).
    if LA in res and deviation(ev, LA, True):
        frame, fixed = _anchored_frame(done, targets[n - 2], s), True
    else:
        frame, fixed = LeaderFrame((0, s), s), False
    _frame_region(ev, frame)
    decision = target_move(frame, n - 1, targets[n - 1], "leader", frame_fixed=fixed)
    return fixed_sign_stride(
        replace(
            decision,
            rule=f"Phase 3 (leader): all others done → {decision.rule}",
            rule_id=f"A3.leader.last-target/{decision.rule_id}",
        ),
        done,
    )


def _up_towards(done: list[Seen]) -> int:
    """The frame's +y as seen by the leader: towards the done robots off its row (+1 if none is)."""
    off_row = [d for d in done if d.dy != 0]
    return (1 if off_row[0].dy > 0 else -1) if off_row else 1


def _anchored_frame(done: list[Seen], t_prev: Point, s: int) -> LeaderFrame:
    """LA: the leader is oblivious, so it re-derives the frame from t_{n−2}, the leftmost robot of the
    lowest visible done row, instead of from its own position. (With s unknown, i.e. every visible done
    robot on the leader's row, the leader is on t_{n−1}'s row and its frame point does not depend on s.)"""
    lowest = min(s * d.dy for d in done)
    b = min((d for d in done if s * d.dy == lowest), key=lambda d: d.dx)
    # b is at frame point t_prev, so the frame's origin in local terms is b − (t_prev.x, s·t_prev.y).
    return LeaderFrame((b.dx - t_prev[0], b.dy - s * t_prev[1]), s)
