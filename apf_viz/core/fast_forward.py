"""Fast-forward: a walk the scheduler cannot interleave, applied as one macro-step.

When exactly one robot can change anything (every other robot's next cycle is "same light, stay", and
each of them is watched), an ASYNC-family scheduler has no choice: it activates that robot's Look,
Compute and Move, again and again. If the robot's decision carries a ``stride`` of n (the algorithm's
promise that the same decision answers the views it will hold after each of its next n − 1 moves, when
nothing else changes), the engine may apply those n cycles at once, provided that

1. nothing else *does* change for the walker: from every point of its walk it sees exactly the robots it
   sees now, with the same lights (:func:`steps_in_same_sight`: no two robots it sees line up with it,
   and every robot it does not see stands on the line of its walk, hidden behind the nearest one there),
   and no point of the walk is occupied;
2. no other robot is concerned: no watch is touched at any step of the walk
   (:meth:`~apf_viz.core.quiet_steps.QuietSteps.quiet_steps`), so every other robot stays ineligible and the
   scheduler's choice stays forced;
3. no budget, step limit or outcome can fall inside the walk.

Then the step-by-step run would produce, event for event, the Looks (the same robots seen), Computes (the
same decision) and Moves (one lattice step each) the macro-step records (docs/ALGORITHM.md,
"Fast-forward"; ``tests/test_fast_forward.py`` compares both runs event for event).

In a crowd, 1 fails within a few steps (a robot hidden off the walk's line is revealed at the next one),
but 2 and 3 alone keep the scheduler's choice forced. The engine then runs the walker's *forced cycles*
(``Engine._forced_cycles``): each with its real Look and Compute, recorded step by step, while the
decision keeps its light and its move; what it spares is the scheduler, the eligibility sweep and the
watches told of every move.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from itertools import combinations

import numpy as np

from apf_viz.core.algorithm import Decision
from apf_viz.core.frames import to_local
from apf_viz.core.grid import Direction, Point, visible_from
from apf_viz.core.view import Columns, Seen, Snapshot

# Products of two offsets fit in int64 below this; larger coordinates are lined up in Python integers.
_SMALL = 1 << 31
# A view of more robots off the walk's line than this (in Python integers only) is not fast-forwarded.
_MANY_PAIRS = 20_000


def along(move: Direction, dx: np.ndarray, dy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Offsets as (progress along ``move``, distance off its line): the walk is then along +u."""
    mx, my = move.delta
    if my == 0:
        return dx * mx, dy
    return dy * my, dx


def steps_in_same_sight(columns: Columns, move: Direction, n: int) -> int:
    """The largest n′ ≤ n such that the walker, moving n′ times by ``move`` from the origin of this view,
    finds each point free and, from each point it decides at (0 … n′ − 1), sees the same robots.

    Assumes every robot missing from the view stands on the walk's line (the engine checks it): those
    stay hidden behind the nearest robot there. A robot off the line stays in sight until two of them
    line up with the walker, i.e. until the walker reaches the point where the line through two robots
    on one side of the walk crosses it."""
    u, v = along(move, columns.dx, columns.dy)
    ahead = u[(v == 0) & (u > 0)]
    if ahead.size:
        n = min(n, int(ahead.min()) - 1)  # the next move would be onto that robot
    off = v != 0
    u, v = u[off], v[off]
    if n < 2 or u.size < 2:
        return n
    big = max(int(np.abs(u).max()), int(np.abs(v).max())) >= _SMALL
    if big:
        if u.size * (u.size - 1) // 2 > _MANY_PAIRS:
            return 1
        return min(n, _first_line_up_exact(u.tolist(), v.tolist(), n))
    if n - 1 < (u.size - 1) // 2:  # fewer points to stand at than pairs to line up: test each point
        return _first_line_up_by_steps(u, v, n)
    return _first_line_up_by_pairs(u, v, n)


def _first_line_up_by_pairs(u: np.ndarray, v: np.ndarray, n: int) -> int:
    """The first point 1 … n − 1 of the walk's line where two robots (all off it) line up with it, else
    n: where the line through each pair on one side crosses the walk (m²/2 pairs for m robots)."""
    i, j = np.triu_indices(u.size, 1)
    va, vb = v[i], v[j]
    same_side = (va * vb > 0) & (va != vb)
    ua, ub, va, vb = u[i][same_side], u[j][same_side], va[same_side], vb[same_side]
    num = ua * vb - ub * va  # the line through a and b crosses v = 0 at u = num / den
    den = vb - va
    exact = num % den == 0
    at = num[exact] // den[exact]
    at = at[(at >= 1) & (at < n)]
    return int(at.min()) if at.size else n


def _first_line_up_by_steps(u: np.ndarray, v: np.ndarray, n: int) -> int:
    """The same answer as :func:`_first_line_up_by_pairs`, point by point: from (t, 0) two robots line
    up when their offsets have one primitive direction (v ≠ 0 for all, so the gcd is positive, and one
    direction means one side). n − 1 points of m robots each: a lone walker's view of 800 robots
    costs 20 ms as pairs, and its walk is a few points long."""
    for t in range(1, n):
        du = u - t
        g = np.gcd(du, v)
        a, b = du // g, v // g
        order = np.lexsort((b, a))
        a, b = a[order], b[order]
        if np.any((a[1:] == a[:-1]) & (b[1:] == b[:-1])):
            return t
    return n


def _first_line_up_exact(u: list[int], v: list[int], n: int) -> int:
    """:func:`steps_in_same_sight`'s line-ups in Python integers (coordinates too large for int64)."""
    first = n
    for (ua, va), (ub, vb) in combinations(zip(u, v, strict=True), 2):
        if va * vb <= 0 or va == vb:
            continue
        num, den = ua * vb - ub * va, vb - va
        if num % den == 0 and 1 <= num // den < first:
            first = num // den
    return first


def hidden_only_on_line(positions: np.ndarray, r: int, delta: Point, seen: Columns) -> bool:
    """Whether every robot that robot r does not see stands on the line of r's walk (global ``delta``,
    one lattice step along an axis): then it stays hidden for the whole walk."""
    hidden = positions.shape[0] - 1 - int(seen.dx.shape[0])
    if not hidden:
        return True
    axis = 1 if delta[1] == 0 else 0  # a horizontal walk keeps y; a vertical one keeps x
    on_line = int(np.count_nonzero(positions[:, axis] == positions[r, axis])) - 1
    seen_on_line = int(np.count_nonzero((seen.dy if axis == 1 else seen.dx) == 0))
    return bool(hidden == on_line - seen_on_line)


def shifted(view: Snapshot, move: Direction, j: int) -> Snapshot:
    """The view after the walker's own j moves by ``move`` when nothing else changed: every offset
    minus j·move (the order by offset is unchanged)."""
    c = view.columns
    mx, my = move.delta
    return Snapshot(view.light, columns=Columns(c.dx - j * mx, c.dy - j * my, c.code, c.palette))


def check_walks_requested() -> bool:
    """Whether ``APF_VIZ_CHECK_WALKS=1`` asks every engine to re-decide the steps it walks."""
    return os.environ.get("APF_VIZ_CHECK_WALKS", "0") not in ("", "0")


class WalkMismatch(AssertionError):
    """A walk (or forced cycles) applied a step the step-by-step run would not have made."""


def snapshot_from_scratch(positions: np.ndarray, lights: Sequence[str], r: int, y_up: bool) -> Snapshot:
    """Robot r's snapshot computed afresh from the positions (no patched view, no cache): the check's
    independent witness of what r would see."""
    here = positions[r]
    robots = []
    for j in visible_from(positions, r).tolist():
        dx, dy = to_local((int(positions[j, 0] - here[0]), int(positions[j, 1] - here[1])), y_up)
        robots.append(Seen(dx, dy, lights[j]))
    return Snapshot(lights[r], tuple(sorted(robots)))


def walk_mismatch(
    positions: np.ndarray,
    lights: Sequence[str],
    y_up: Sequence[bool],
    r: int,
    delta: Point,
    n: int,
    decision: Decision | None,
    decide: Callable[[Snapshot], Decision],
) -> str | None:
    """What the step-by-step run would do differently from n cycles of robot r walking by ``delta``
    (global) from where ``positions`` has it, or None if nothing: at each of its points 1 … n − 1 the
    walker decides ``decision`` again on its real view (skipped when None: forced cycles decide each
    cycle for real), and at each of those points every other robot's real view is still answered with "same
    light, stay" (else the scheduler would have had a choice). Costs n·k decisions on views built from
    scratch: for ``APF_VIZ_CHECK_WALKS=1`` and ``--check-walks``, not for ordinary runs."""
    at = positions.copy()
    x, y = int(at[r, 0]), int(at[r, 1])
    for j in range(1, n):  # after its last move the walk is over: others may then act
        at[r] = (x + j * delta[0], y + j * delta[1])
        if decision is not None:
            again = decide(snapshot_from_scratch(at, lights, r, y_up[r]))
            if again != decision:
                return (
                    f"robot {r} walked from ({x}, {y}) by {delta} for {n} cycles on {decision.rule_id!r}, "
                    f"but at its cycle {j + 1} decides {again.rule_id!r} ({again.light}, {again.move})"
                )
        for o in range(at.shape[0]):
            if o == r:
                continue
            other = decide(snapshot_from_scratch(at, lights, o, y_up[o]))
            if not other.is_noop(lights[o]):
                return (
                    f"robot {r}'s walk from ({x}, {y}) by {delta}: after its move {j} of {n}, robot {o} "
                    f"would act ({other.rule_id!r}), so the scheduler had a choice"
                )
    return None
