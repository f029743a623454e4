"""The explorer's states and the adversary's transitions between them.

A state is one flat tuple of small integers: every robot's canonical position (translated so that
min x = min y = 0; robots keep their indices, which fairness needs), then every robot's light (an index
into :attr:`Decisions.lights`), then every robot's *code*, what it holds between events:

- ``0``: idle;
- ``2d + 1``: it has Looked, and its snapshot leads to decision ``d`` (the light is not yet shown);
- ``2d + 2``: it has Computed, and the move of decision ``d`` is pending.

Holding the decision instead of the snapshot is exact: the algorithm is a pure function of the snapshot,
and nothing else of the snapshot is used later. A flat tuple of integers is the cheapest key Python hashes
and compares (a nested tuple's hash is not cached and is recomputed level by level); a state is about
``4k + 1`` machine words. The translation removed from a state (its *origin*) is not part of it: the
search keeps it beside the state, for the box and the messages.
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from itertools import combinations, pairwise, repeat
from math import gcd

import numpy as np

from apf_viz.core.algorithm import Algorithm, Decision
from apf_viz.core.frames import move_to_global
from apf_viz.core.grid import Point
from apf_viz.core.view import Seen, Snapshot

State = tuple[int, ...]
Box = tuple[int, int, int, int]


class Violation(Exception):
    """A transition that collides or escapes: its message ("collision: …", "escape: …") and the robots
    acting. Raised, not returned: the search then tests nothing per edge."""

    def __init__(self, message: str, robots: tuple[int, ...]) -> None:
        super().__init__(message)
        self.robots = robots


def decision_of(code: int) -> int:
    """The decision a non-idle code holds (``2d + 1`` and ``2d + 2`` both give ``d``)."""
    return (code - 1) >> 1


class Decisions:
    """What the searches from one start share, whatever the flips: a robot's decision depends on its
    snapshot alone (the view memo), or on the configuration, which robot it is and its own flip (the
    configuration memo), never on the other robots' flips; the decisions and lights as small integers,
    with each decision's light and global move (per flip) read off once."""

    def __init__(self) -> None:
        self.by_view: dict[Snapshot, int] = {}
        self.by_configuration: dict[tuple, int] = {}
        self.index: dict[Decision, int] = {}
        self.table: list[Decision] = []
        self.light: list[int] = []  # per decision: its light's index
        self.stays: list[bool] = []  # per decision: no move
        self.moves: dict[bool, list[Point | None]] = {True: [], False: []}  # per flip, per decision
        self.lights: list[str] = []
        self.light_ids: dict[str, int] = {}

    def light_id(self, name: str) -> int:
        i = self.light_ids.get(name)
        if i is None:
            i = self.light_ids[name] = len(self.lights)
            self.lights.append(name)
        return i

    def intern(self, decision: Decision) -> int:
        i = self.index.get(decision)
        if i is None:
            i = self.index[decision] = len(self.table)
            self.table.append(decision)
            self.light.append(self.light_id(decision.light))
            self.stays.append(decision.move is None)
            for y_up, moves in self.moves.items():
                move = move_to_global(decision.move, y_up)
                moves.append(None if move is None else move.delta)
        return i


def visible(positions: Sequence[Point], i: int) -> list[int]:
    """Nearest robot per primitive direction (pure Python: the explorer's k is small)."""
    x0, y0 = positions[i]
    best: dict[Point, tuple[int, int]] = {}
    for j, (x, y) in enumerate(positions):
        if j == i:
            continue
        dx, dy = x - x0, y - y0
        g = gcd(abs(dx), abs(dy))
        d = (dx // g, dy // g)
        if d not in best or g < best[d][0]:
            best[d] = (g, j)
    return [j for _, j in best.values()]


SIGHT_CACHE = 20_000  # positions whose sight lines are kept (about 2 kB each at k = 30)
SIGHT_LINES_FROM = 8
"""From this many robots on, views are read off :func:`sight_lines` (numpy, every robot at once); below,
:func:`visible` per robot is quicker (docs/PERFORMANCE.md, "The hunt")."""


def sight_lines(flat: Sequence[int]) -> list[tuple[list[int], list[int], list[int], list[int]]]:
    """For each robot of the flat positions (x0, y0, x1, y1, …), what it sees: the nearest robot along
    each primitive direction (dx, dy)/gcd, for all robots at once, in exact integer arithmetic. Per robot:
    the offsets dx and dy and the indices of the robots it sees, sorted by (dx, dy), and the permutation
    of them that sorts by (dx, −dy) (the order a robot whose y-axis is flipped sees)."""
    p = np.asarray(flat, dtype=np.int64).reshape(-1, 2)
    k = p.shape[0]
    dx = p[None, :, 0] - p[:, None, 0]  # [observer, other]
    dy = p[None, :, 1] - p[:, None, 1]
    g = np.gcd(dx, dy)
    np.fill_diagonal(g, 1)
    ux, uy = dx // g, dy // g
    span = int(max(np.abs(ux).max(), np.abs(uy).max())) + 1
    direction = (ux + span) * (2 * span + 1) + (uy + span)  # one integer per primitive direction
    observer = np.repeat(np.arange(k), k)
    other = np.tile(np.arange(k), k)
    keep = observer != other
    observer, other = observer[keep], other[keep]
    direction, dist = direction.ravel()[keep], g.ravel()[keep]
    order = np.lexsort((dist, direction, observer))  # by observer, direction, then nearest first
    o, d = observer[order], direction[order]
    first = np.ones(o.size, dtype=bool)
    first[1:] = (o[1:] != o[:-1]) | (d[1:] != d[:-1])
    o, j = o[first], other[order][first]
    sx, sy = p[j, 0] - p[o, 0], p[j, 1] - p[o, 1]
    up = np.lexsort((sy, sx, o))
    o, j, sx, sy = o[up], j[up], sx[up], sy[up]
    flipped = np.lexsort((-sy, sx, o))  # within one observer, a permutation of its own entries
    bounds = np.searchsorted(o, np.arange(k + 1)).tolist()
    xs, ys, js, fl = sx.tolist(), sy.tolist(), j.tolist(), flipped.tolist()
    return [(xs[a:b], ys[a:b], js[a:b], [i - a for i in fl[a:b]]) for a, b in pairwise(bounds)]


def canonical(positions: Sequence[int], origin: Point) -> tuple[tuple[int, ...], Point]:
    """Flat positions translated so that min x = min y = 0, and the origin that translation adds."""
    mx, my = min(positions[0::2]), min(positions[1::2])
    if mx == my == 0:
        return tuple(positions), origin
    shifted = tuple(v - (my if i & 1 else mx) for i, v in enumerate(positions))
    return shifted, (origin[0] + mx, origin[1] + my)


class StateSpace:
    """The transitions of one search: one start, one assignment of flips, one scheduler."""

    def __init__(
        self,
        algorithm: Algorithm,
        pattern: tuple[Point, ...],
        y_up: tuple[bool, ...],
        scheduler: str,
        lc_atomic: bool,
        reduction: bool,
        decisions: Decisions,
        box: Box,
    ) -> None:
        self.algorithm = algorithm
        self.pattern = pattern
        self.y_up = y_up
        self.k = len(y_up)
        self.scheduler = scheduler
        self.lc_atomic = lc_atomic
        self.reduction = reduction
        self.memo = decisions
        self.box = box
        self._quiet: dict[State, bool] = {}  # configuration → every robot's decision is a no-op
        self._sight: dict[State, list] = {}  # positions → each robot's sight lines (sight_lines)
        # Each state's edges are labelled by one of these shared tuples (no tuple per edge).
        self.singles = tuple((r,) for r in range(self.k))
        self.alone = tuple((s,) for s in self.singles)

    # ------------------------------------------------------------------ reading a state
    def initial(self, robots: Sequence[Point]) -> tuple[State, Point]:
        flat, origin = canonical([v for p in robots for v in p], (0, 0))
        first = self.memo.light_id(self.algorithm.lights[0])
        return flat + (first,) * self.k + (0,) * self.k, origin

    def positions(self, st: State, origin: Point = (0, 0)) -> list[Point]:
        return [(st[2 * r] + origin[0], st[2 * r + 1] + origin[1]) for r in range(self.k)]

    def configuration(self, st: State) -> tuple[tuple[Point, ...], tuple[str, ...]]:
        """Positions and light names, as a person (or a test) reads them."""
        names = self.memo.lights
        return tuple(self.positions(st)), tuple(names[i] for i in st[2 * self.k : 3 * self.k])

    # ------------------------------------------------------------------ decisions
    def decide(self, cfg: State, r: int) -> int:
        """Robot r's decision on the configuration ``cfg`` (a state's positions and lights); memoised
        on (configuration, r, r's flip): many states differ only in what robots hold, and many flip
        assignments reach the same configurations."""
        key = (cfg, r if self.y_up[r] else -1 - r)
        d = self.memo.by_configuration.get(key)
        if d is None:
            d = self.memo.by_configuration[key] = self._decide_uncached(cfg, r)
        return d

    def _decide_uncached(self, cfg: State, r: int) -> int:
        names = self.memo.lights
        lights = [names[i] for i in cfg[2 * self.k : 3 * self.k]]
        if self.k < SIGHT_LINES_FROM:
            positions = self.positions(cfg)
            x0, y0 = positions[r]
            s = 1 if self.y_up[r] else -1
            seen = tuple(
                sorted(
                    Seen(positions[j][0] - x0, s * (positions[j][1] - y0), lights[j])
                    for j in visible(positions, r)
                )
            )
        else:
            seen = self._seen_from_sight_lines(cfg, r, lights)
        view = Snapshot(lights[r], seen)
        d = self.memo.by_view.get(view)
        if d is None:
            d = self.memo.by_view[view] = self.memo.intern(self.algorithm.decide(view, self.pattern))
        return d

    def _seen_from_sight_lines(self, cfg: State, r: int, lights: list[str]) -> tuple[Seen, ...]:
        """r's view from the configuration's sight lines (:func:`sight_lines`, made once for all its
        robots and every light: they depend on the positions only), sorted by (dx, dy) in r's frame."""
        at = cfg[: 2 * self.k]
        lines = self._sight.get(at)
        if lines is None:
            if len(self._sight) > SIGHT_CACHE:  # a cache of the positions being expanded lately
                self._sight.clear()
            lines = self._sight[at] = sight_lines(at)
        dx, dy, who, flipped = lines[r]
        # tuple.__new__ mapped in C: a NamedTuple's own __new__ is a Python function, many times slower.
        if self.y_up[r]:
            return tuple(map(tuple.__new__, repeat(Seen), zip(dx, dy, [lights[j] for j in who], strict=True)))
        return tuple(map(tuple.__new__, repeat(Seen), [(dx[i], -dy[i], lights[who[i]]) for i in flipped]))

    def forget(self) -> None:
        """Drop what is remembered per configuration (the decisions' table, which states refer to,
        stays): a search that walks far from where it began keeps its memory bounded."""
        self.memo.by_configuration.clear()
        self.memo.by_view.clear()
        self._quiet.clear()
        self._sight.clear()

    def quiescent(self, st: State) -> bool:
        """No robot can change anything: every held decision and every decision on the current view
        keeps the light and stays, and no move is pending."""
        k, light, stays = self.k, self.memo.light, self.memo.stays
        for r in range(k):
            c = st[3 * k + r]
            if c:
                d = (c - 1) >> 1
                if not stays[d] or (c & 1 and light[d] != st[2 * k + r]):
                    return False
        return self._all_noop(st[: 3 * k])

    def _all_noop(self, cfg: State) -> bool:
        """Every robot's decision on this configuration keeps its light and stays (many states share a
        configuration: asked once for each)."""
        quiet = self._quiet.get(cfg)
        if quiet is None:
            k, light, stays = self.k, self.memo.light, self.memo.stays
            quiet = True
            for r in range(k):
                d = self.decide(cfg, r)
                if not stays[d] or light[d] != cfg[2 * k + r]:
                    quiet = False
                    break
            self._quiet[cfg] = quiet
        return quiet

    def eligible(self, st: State) -> list[int]:
        """The robots whose next event can change anything (the engine's ``eligible``): every robot that
        has Looked or Computed, and every idle one whose decision on its view now is not "same light,
        stay". Activating another is a whole cycle that changes nothing, which a scheduler that skips
        no-ops never makes."""
        k, light, stays = self.k, self.memo.light, self.memo.stays
        cfg = st[: 3 * k]
        out = []
        for r in range(k):
            if st[3 * k + r]:
                out.append(r)
                continue
            d = self.decide(cfg, r)
            if not stays[d] or light[d] != st[2 * k + r]:
                out.append(r)
        return out

    def invisible(self, st: State) -> int | None:
        """The first robot whose next event is invisible: a Compute that keeps its light, or a Move that
        stays. Such an event reads nothing another robot writes and writes nothing another robot reads
        (only its own code), and its robot has no other event: it commutes with every event of the
        others, so exploring it alone loses no configuration, violation or fair cycle (the argument:
        docs/VERIFICATION.md, "Partial-order reduction")."""
        k, light, stays = self.k, self.memo.light, self.memo.stays
        for r in range(k):
            c = st[3 * k + r]
            if c:
                d = (c - 1) >> 1
                if (light[d] == st[2 * k + r]) if c & 1 else stays[d]:
                    return r
        return None

    @functools.cached_property
    def groups(self) -> tuple[tuple[int, ...], ...]:
        """The groups a round may take: all robots (FSYNC) or every non-empty subset (SSYNC). Made only
        when a round is explored: under ASYNC there are none, and 2^k subsets of k = 30 robots would not
        fit in memory."""
        if self.scheduler == "fsync":
            return (tuple(range(self.k)),)
        return tuple(c for n in range(1, self.k + 1) for c in combinations(range(self.k), n))

    @property
    def labels(self) -> tuple:
        """The robots acting on each edge of a state expanded in full (a reduced state has one edge, its
        robot's): what the edges before a violation are labelled by."""
        return self.singles if self.scheduler == "async" else self.groups

    # ------------------------------------------------------------------ transitions
    def successors(self, st: State, origin: Point, out: list[tuple[State, Point]]) -> tuple:
        """Appends each edge's (next state, its origin) to ``out`` and returns the robots acting on each
        edge; raises :class:`Violation` at the first edge that violates (``out`` then holds the edges
        before it)."""
        if self.scheduler != "async":
            for g in self.groups:
                out.append(self._round(st, origin, g))
            return self.groups
        if self.reduction:
            r = self.invisible(st)
            if r is not None:
                out.append(self.event(st, origin, r))
                return self.alone[r]
        event = self.event
        for r in range(self.k):
            out.append(event(st, origin, r))
        return self.singles

    def edge(self, st: State, origin: Point, group: tuple[int, ...]) -> tuple[State, Point]:
        """One edge: ``group`` acts (a robot's next event under ASYNC, a round otherwise); raises
        :class:`Violation` if it collides or escapes."""
        if self.scheduler == "async":
            return self.event(st, origin, group[0])
        return self._round(st, origin, group)

    def event(self, st: State, origin: Point, r: int) -> tuple[State, Point]:
        """Robot r's next event under ASYNC: a Look, a Compute or a Move. (A state is copied to a list,
        changed and frozen: faster than splicing tuples.)"""
        k = self.k
        at = 3 * k + r
        c = st[at]
        nxt = list(st)
        if c == 0:  # Look; decisions depend on offsets only, so canonical positions serve
            d = self.decide(st[: 3 * k], r)
            nxt[at] = 2 * d + 1
            if self.lc_atomic:  # Look and Compute are one event: the light shows from the Look
                nxt[2 * k + r] = self.memo.light[d]
                nxt[at] = 2 * d + 2
            return tuple(nxt), origin
        d = (c - 1) >> 1
        if c & 1:  # Compute: the decision's light shows
            nxt[2 * k + r] = self.memo.light[d]
            nxt[at] = c + 1
            return tuple(nxt), origin
        move = self.memo.moves[self.y_up[r]][d]
        nxt[at] = 0
        if move is None:  # a Move that stays: the configuration, hence its canonical form, is unchanged
            return tuple(nxt), origin
        return self._move(nxt, origin, r, move)

    def _move(self, nxt: list[int], origin: Point, r: int, move: Point) -> tuple[State, Point]:
        k = self.k
        x, y = nxt[2 * r] + move[0], nxt[2 * r + 1] + move[1]
        ox, oy = origin
        for j in range(k):
            if nxt[2 * j] == x and nxt[2 * j + 1] == y:
                raise Violation(f"collision: robot {r} moves onto robot {j} at {(x + ox, y + oy)}", (r,))
        if not self.inside((x + ox, y + oy)):
            raise Violation(f"escape: robot {r} left the box at {(x + ox, y + oy)}", (r,))
        nxt[2 * r], nxt[2 * r + 1] = x, y
        mx, my = min(nxt[0 : 2 * k : 2]), min(nxt[1 : 2 * k : 2])
        if mx or my:
            for j in range(k):
                nxt[2 * j] -= mx
                nxt[2 * j + 1] -= my
            origin = (ox + mx, oy + my)
        return tuple(nxt), origin

    def _round(self, st: State, origin: Point, group: tuple[int, ...]) -> tuple[State, Point]:
        """One atomic cycle of ``group`` (SSYNC, FSYNC): Looks, then Computes, then simultaneous Moves."""
        k = self.k
        cfg = st[: 3 * k]
        pos = self.positions(st, origin)
        lights = list(st[2 * k : 3 * k])
        decided = {r: self.decide(cfg, r) for r in group}
        targets = {}
        for r, d in decided.items():
            lights[r] = self.memo.light[d]
            move = self.memo.moves[self.y_up[r]][d]
            targets[r] = pos[r] if move is None else (pos[r][0] + move[0], pos[r][1] + move[1])
        new = list(pos)
        for r, t in targets.items():
            new[r] = t
        if len(set(new)) < k:
            raise Violation("collision: two robots on one point after the round", group)
        for r, t in targets.items():
            other = next((q for q in targets if q != r and targets[q] == pos[r] and t == pos[q]), None)
            if other is not None:
                raise Violation(f"collision: robots {r} and {other} swap across an edge", group)
            if not self.inside(t):
                raise Violation(f"escape: robot {r} left the box at {t}", group)
        flat, moved = canonical([v for p in new for v in p], (0, 0))
        return flat + tuple(lights) + (0,) * k, moved

    def inside(self, p: Point) -> bool:
        x0, y0, x1, y1 = self.box
        return x0 <= p[0] <= x1 and y0 <= p[1] <= y1
