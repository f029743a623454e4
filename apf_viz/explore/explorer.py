"""Exhaustive schedule exploration: every execution the adversary can produce from a small start.

A state is the configuration with robot identities (fairness needs them), every robot's light and phase,
and what a robot holds between events: after its Look the decision its snapshot leads to (the light is not
yet shown), after its Compute the pending move. Holding the decision instead of the snapshot is exact:
the algorithm is a pure function of the snapshot, and nothing else of the snapshot is used later.
States are canonical up to translation (the algorithm sees offsets only, and moves are relative).

ASYNC: from a state each robot's next event is one transition (k successors). SSYNC: each non-empty set
of robots runs one atomic cycle (Looks, then Computes, then simultaneous Moves). FSYNC: everyone.

Verdicts: ``collision``; ``escape`` (a robot left the box around start ∪ pattern, so the search is not
finite); ``deadlock`` (a terminal state that is not the pattern); ``livelock`` (a strongly connected set of
states, not all quiescent, in which every robot acts: a fair execution that never ends); ``budget`` (the
state limit was hit first: nothing is proved); ``verified``.
"""

from __future__ import annotations

import time
from collections import deque
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from itertools import combinations
from math import gcd
from typing import Literal

from apf_viz.core.algorithm import Algorithm, Decision
from apf_viz.core.frames import move_to_global
from apf_viz.core.grid import Point, as_point
from apf_viz.core.pattern_match import matches_pattern
from apf_viz.core.view import Seen, Snapshot

Verdict = Literal["verified", "collision", "escape", "deadlock", "livelock", "budget"]
IDLE, LOOKED, COMPUTED = 0, 1, 2


@dataclass(frozen=True, slots=True)
class State:
    """Canonical state: positions translated so that min x = min y = 0 (robots keep their indices)."""

    positions: tuple[Point, ...]
    lights: tuple[str, ...]
    phases: tuple[int, ...]
    # LOOKED: the decision its snapshot leads to; COMPUTED: its pending move; as an index of
    # Decisions.table (a state's key then hashes small ints, not decisions); NONE when idle
    held: tuple[int, ...]
    origin: Point  # the translation removed (not part of equality)

    def key(self) -> tuple:
        return (self.positions, self.lights, self.phases, self.held)


@dataclass
class Result:
    verdict: Verdict
    states: int
    transitions: int
    seconds: float
    schedule: list[tuple[int, ...]] = field(default_factory=list)  # robots per step, from the start
    loop_start: int | None = None  # for a livelock: the step index where the repeated part begins
    detail: str = ""


NONE = -1  # a state's held entry for a robot that holds nothing (idle)


class Decisions:
    """What the searches from one start share, whatever the flips: a robot's decision depends on its
    snapshot alone (the view memo), or on the configuration, which robot it is and its own flip (the
    configuration memo), never on the other robots' flips; and the decisions as small integers."""

    def __init__(self) -> None:
        self.by_view: dict[Snapshot, int] = {}
        self.by_configuration: dict[tuple, int] = {}
        self.index: dict[Decision, int] = {}
        self.table: list[Decision] = []

    def intern(self, decision: Decision) -> int:
        i = self.index.get(decision)
        if i is None:
            i = self.index[decision] = len(self.table)
            self.table.append(decision)
        return i


def _canonical(positions: Sequence[Point], lights, phases, held, origin: Point) -> State:
    xs, ys = zip(*positions, strict=True)
    mx, my = min(xs), min(ys)
    pts = tuple(positions) if mx == my == 0 else tuple((x - mx, y - my) for x, y in positions)
    return State(pts, tuple(lights), tuple(phases), tuple(held), (origin[0] + mx, origin[1] + my))


def _visible(positions: Sequence[Point], i: int) -> list[int]:
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


class Explorer:
    """Breadth-first search of the adversary's choices from one start (and one assignment of flips)."""

    def __init__(
        self,
        algorithm: Algorithm,
        robots: Sequence[Point],
        pattern: Sequence[Point],
        y_up: Sequence[bool],
        *,
        scheduler: Literal["async", "ssync", "fsync"] = "async",
        max_states: int = 1_000_000,
        margin: int | None = None,
        light_semantics: Literal["compute", "lc-atomic"] = "compute",
        progress: Callable[[int, int, float], None] | None = None,
        reduction: bool = False,
        decisions: Decisions | None = None,
    ) -> None:
        self.algorithm = algorithm
        self.robots = [as_point(p) for p in robots]
        self.pattern = tuple(as_point(p) for p in pattern)
        self.y_up = tuple(y_up)
        self.k = len(self.robots)
        self.scheduler = scheduler
        self.max_states = max_states
        self.progress = progress
        self.lc_atomic = light_semantics == "lc-atomic"
        # Partial-order reduction (docs/VERIFICATION.md): only under ASYNC, where one event is one robot's.
        self.reduction = reduction and scheduler == "async"
        # Shared by the searches of one start under several flips (explore/check.py), or this one's own.
        self._memo = decisions if decisions is not None else Decisions()
        self._table = self._memo.table
        self._quiet: dict[tuple, bool] = {}  # configuration → every robot's decision is a no-op
        pts = self.robots + list(self.pattern)
        span = max(
            max(p[0] for p in pts) - min(p[0] for p in pts), max(p[1] for p in pts) - min(p[1] for p in pts)
        )
        # The paper's moves stay within O(kD) of the start; a box this much wider than start ∪ pattern is
        # generous for the starts the explorer can handle, and keeps the state space finite.
        self.margin = margin if margin is not None else 2 * (self.k + span) + 4
        self._box = (
            min(p[0] for p in self.robots) - self.margin,
            min(p[1] for p in self.robots) - self.margin,
            max(p[0] for p in self.robots) + self.margin,
            max(p[1] for p in self.robots) + self.margin,
        )

    # ------------------------------------------------------------------ transitions
    def initial(self) -> State:
        first = self.algorithm.lights[0]
        return _canonical(self.robots, [first] * self.k, [IDLE] * self.k, [NONE] * self.k, (0, 0))

    def _decide(self, positions: Sequence[Point], lights: Sequence[str], r: int) -> Decision:
        return self._table[self._decide_id(positions, lights, r)]

    def _decide_id(self, positions: Sequence[Point], lights: Sequence[str], r: int) -> int:
        """Robot r's decision on this configuration (its index in the table); memoised on (configuration,
        r, r's flip): many states differ only in phases and held decisions, and many flip assignments
        reach the same configurations."""
        key = (tuple(positions), tuple(lights), r, self.y_up[r])
        d = self._memo.by_configuration.get(key)
        if d is None:
            d = self._memo.by_configuration[key] = self._decide_uncached(positions, lights, r)
        return d

    def _decide_uncached(self, positions: Sequence[Point], lights: Sequence[str], r: int) -> int:
        x0, y0 = positions[r]
        s = 1 if self.y_up[r] else -1
        seen = sorted(
            Seen(positions[j][0] - x0, s * (positions[j][1] - y0), lights[j]) for j in _visible(positions, r)
        )
        view = Snapshot(lights[r], tuple(seen))
        d = self._memo.by_view.get(view)
        if d is None:
            d = self._memo.by_view[view] = self._memo.intern(self.algorithm.decide(view, self.pattern))
        return d

    def successors(self, st: State) -> list[tuple[tuple[int, ...], State | str]]:
        """(robots acting, next state) pairs; a violation is a string instead of a state."""
        if self.scheduler == "async":
            r = self._invisible(st) if self.reduction else None
            if r is not None:
                return [((r,), self._event(st, r))]
            return [((r,), self._event(st, r)) for r in range(self.k)]
        groups = (
            [tuple(range(self.k))]
            if self.scheduler == "fsync"
            else [c for n in range(1, self.k + 1) for c in combinations(range(self.k), n)]
        )
        return [(g, self._round(st, g)) for g in groups]

    def _invisible(self, st: State) -> int | None:
        """The first robot whose next event is invisible: a Compute that keeps its light, or a Move that
        stays. Such an event reads nothing another robot writes and writes nothing another robot reads
        (only its own phase and held decision), and its robot has no other event: it commutes with every
        event of the others, so exploring it alone loses no configuration, violation or fair cycle (the
        argument: docs/VERIFICATION.md, "Partial-order reduction")."""
        table = self._table
        for r in range(self.k):
            phase = st.phases[r]
            if phase == LOOKED and table[st.held[r]].light == st.lights[r]:
                return r
            if phase == COMPUTED and table[st.held[r]].move is None:
                return r
        return None

    def _event(self, st: State, r: int) -> State | str:
        phases, held = list(st.phases), list(st.held)
        if phases[r] == IDLE:
            # Decisions depend on offsets only: the canonical positions serve as well as absolute ones.
            held[r] = self._decide_id(st.positions, st.lights, r)
            phases[r] = LOOKED
            lights = st.lights
            if self.lc_atomic:  # Look and Compute are one event: the light shows from the Look
                lights = (*lights[:r], self._table[held[r]].light, *lights[r + 1 :])
                phases[r] = COMPUTED
            return State(st.positions, lights, tuple(phases), tuple(held), st.origin)
        if phases[r] == LOOKED:
            phases[r] = COMPUTED
            lights = (*st.lights[:r], self._table[held[r]].light, *st.lights[r + 1 :])
            return State(st.positions, lights, tuple(phases), tuple(held), st.origin)
        move = move_to_global(self._table[held[r]].move, self.y_up[r])
        phases[r], held[r] = IDLE, NONE
        if move is None:  # a Move that stays: the configuration, hence its canonical form, is unchanged
            return State(st.positions, st.lights, tuple(phases), tuple(held), st.origin)
        # In the state's canonical coordinates; absolute ones (+ origin) only for the box and the messages.
        x, y = st.positions[r]
        to = (x + move.delta[0], y + move.delta[1])
        ox, oy = st.origin
        if to in st.positions:
            at = (to[0] + ox, to[1] + oy)
            return f"collision: robot {r} moves onto robot {st.positions.index(to)} at {at}"
        at = (to[0] + ox, to[1] + oy)
        if not self._inside(at):
            return f"escape: robot {r} left the box at {at}"
        pos = list(st.positions)
        pos[r] = to
        return _canonical(pos, st.lights, phases, held, st.origin)

    def _round(self, st: State, group: tuple[int, ...]) -> State | str:
        pos = [(x + st.origin[0], y + st.origin[1]) for x, y in st.positions]
        lights = list(st.lights)
        decisions = {r: self._decide(pos, lights, r) for r in group}
        for r, d in decisions.items():
            lights[r] = d.light
        targets = {}
        for r, d in decisions.items():
            move = move_to_global(d.move, self.y_up[r])
            targets[r] = pos[r] if move is None else (pos[r][0] + move.delta[0], pos[r][1] + move.delta[1])
        new = list(pos)
        for r, t in targets.items():
            new[r] = t
        if len(set(new)) < self.k:
            return "collision: two robots on one point after the round"
        for r, t in targets.items():
            other = next((q for q in targets if q != r and targets[q] == pos[r] and t == pos[q]), None)
            if other is not None:
                return f"collision: robots {r} and {other} swap across an edge"
            if not self._inside(t):
                return f"escape: robot {r} left the box at {t}"
        return _canonical(new, lights, [IDLE] * self.k, [NONE] * self.k, (0, 0))

    def _inside(self, p: Point) -> bool:
        x0, y0, x1, y1 = self._box
        return x0 <= p[0] <= x1 and y0 <= p[1] <= y1

    def quiescent(self, st: State) -> bool:
        """No robot can change anything: every held decision and every decision on the current view
        keeps the light and stays, and no move is pending."""
        for r in range(self.k):
            if st.held[r] != NONE:
                h = self._table[st.held[r]]
                if h.move is not None or (st.phases[r] == LOOKED and h.light != st.lights[r]):
                    return False
        return self._all_noop(st.positions, st.lights)

    def _all_noop(self, positions: tuple[Point, ...], lights: tuple[str, ...]) -> bool:
        """Every robot's decision on this configuration keeps its light and stays (many states share a
        configuration: asked once for each)."""
        key = (positions, lights)
        quiet = self._quiet.get(key)
        if quiet is None:
            quiet = self._quiet[key] = all(
                self._decide(positions, lights, r).is_noop(lights[r]) for r in range(self.k)
            )
        return quiet

    # ------------------------------------------------------------------ search
    def run(self) -> Result:
        """The verdict: every reachable state searched (breadth first), then the terminal states that are
        not the pattern (deadlocks) and the fair cycles that never become quiescent (livelocks)."""
        t0 = time.perf_counter()
        if matches_pattern(self.robots, self.pattern):  # the engine's rule: formed before anyone acts
            return Result("verified", 1, 0, 0.0, detail="the start is already the pattern: formed at time 0")
        searched = self._search(t0)
        if isinstance(searched, Result):
            return searched  # a collision, an escape, or the state budget
        states, parent, edges, transitions = searched
        quiet = [self.quiescent(s) for s in states]
        for i, s in enumerate(states):
            if quiet[i] and not matches_pattern(self._absolute(s), self.pattern):
                return self._fail(
                    "deadlock",
                    "a terminal state that is not the pattern",
                    i,
                    None,
                    parent,
                    len(states),
                    transitions,
                    t0,
                )
        loop = self._fair_cycle(edges, quiet)
        seconds = time.perf_counter() - t0
        if loop is not None:
            entry, cycle = loop
            stem = self._path(parent, entry)
            return Result(
                "livelock",
                len(states),
                transitions,
                seconds,
                stem + cycle,
                loop_start=len(stem),
                detail="a fair cycle of states that never becomes quiescent",
            )
        return Result("verified", len(states), transitions, seconds)

    def _search(self, t0: float) -> Result | tuple[list[State], list, list, int]:
        """Every state reachable from the start, breadth first: (states, parents, edges, transitions), or
        the Result that stopped the search (a collision, an escape past the coordinates, the budget)."""
        start = self.initial()
        index: dict[tuple, int] = {start.key(): 0}
        states: list[State] = [start]
        parent: list[tuple[int, tuple[int, ...]] | None] = [None]
        edges: list[list[tuple[tuple[int, ...], int]]] = []
        queue = deque([0])
        transitions = 0
        while queue:
            i = queue.popleft()
            st = states[i]
            out: list[tuple[tuple[int, ...], int]] = []
            for robots, nxt in self.successors(st):
                transitions += 1
                if isinstance(nxt, str):
                    return self._fail(
                        "collision" if nxt.startswith("collision") else "escape",
                        nxt,
                        i,
                        robots,
                        parent,
                        len(states),
                        transitions,
                        t0,
                    )
                key = nxt.key()
                j = index.get(key)
                if j is None:
                    if len(states) >= self.max_states:
                        return Result(
                            "budget",
                            len(states),
                            transitions,
                            time.perf_counter() - t0,
                            detail=f"stopped at {self.max_states} states: nothing is proved",
                        )
                    j = index[key] = len(states)
                    states.append(nxt)
                    parent.append((i, robots))
                    queue.append(j)
                out.append((robots, j))
            edges.append(out)
            if self.progress and len(edges) % 20_000 == 0:
                self.progress(len(states), len(queue), time.perf_counter() - t0)
        return states, parent, edges, transitions

    def _absolute(self, s: State) -> list[Point]:
        return [(x + s.origin[0], y + s.origin[1]) for x, y in s.positions]

    def _path(self, parent, i: int) -> list[tuple[int, ...]]:
        steps = []
        while parent[i] is not None:
            i, robots = parent[i]
            steps.append(robots)
        return steps[::-1]

    def _fail(self, verdict, detail, i, robots, parent, n, transitions, t0) -> Result:
        schedule = self._path(parent, i) + ([robots] if robots is not None else [])
        return Result(verdict, n, transitions, time.perf_counter() - t0, schedule, detail=detail)

    def _fair_cycle(self, edges, quiet) -> tuple[int, list[tuple[int, ...]]] | None:
        """A strongly connected component, not all quiescent, with an edge of every robot inside it;
        returned as (entry state, a cycle from it that lets every robot act)."""
        for comp in _sccs(edges):
            members = set(comp)
            if all(quiet[i] for i in comp):
                continue
            inner = [(i, robots, j) for i in comp for robots, j in edges[i] if j in members]
            if not inner:
                continue
            actors = {r for _, robots, _ in inner for r in robots}
            if actors != set(range(self.k)):
                continue
            entry = min(comp)
            return entry, self._tour(entry, members, edges)
        return None

    def _tour(self, entry: int, members: set[int], edges) -> list[tuple[int, ...]]:
        """Inside one component: from ``entry``, take an edge of every robot in turn, then come back."""
        path: list[tuple[int, ...]] = []
        here = entry
        for r in range(self.k):
            steps, here = self._bfs(here, members, edges, lambda robots, r=r: r in robots)
            path += steps
        steps, here = self._bfs(here, members, edges, None, target=entry)
        return path + steps

    @staticmethod
    def _bfs(src, members, edges, want, target=None):
        """Shortest path inside ``members`` ending with an edge satisfying ``want`` (or at ``target``)."""
        if target is not None and src == target:
            return [], src
        prev: dict[int, tuple[int, tuple[int, ...]] | None] = {src: None}  # node → (node before, edge)
        queue = deque([src])
        while queue:
            i = queue.popleft()
            for robots, j in edges[i]:
                if j not in members:
                    continue
                if want is not None and want(robots):
                    steps = [robots]
                    node = i
                    while (back := prev[node]) is not None:
                        node, rb = back
                        steps.append(rb)
                    return steps[::-1], j
                if j not in prev:
                    prev[j] = (i, robots)
                    if target is not None and j == target:
                        steps, node = [], j
                        while (back := prev[node]) is not None:
                            node, rb = back
                            steps.append(rb)
                        return steps[::-1], j
                    queue.append(j)
        raise AssertionError("component is not strongly connected")


def _sccs(edges: list[list[tuple[tuple[int, ...], int]]]) -> list[list[int]]:
    """Tarjan's algorithm, iterative."""
    n = len(edges)
    index = [-1] * n
    low = [0] * n
    on = [False] * n
    stack: list[int] = []
    out: list[list[int]] = []
    counter = 0
    for root in range(n):
        if index[root] != -1:
            continue
        work = [(root, 0)]
        while work:
            v, pi = work.pop()
            if pi == 0:
                index[v] = low[v] = counter
                counter += 1
                stack.append(v)
                on[v] = True
            advanced = False
            for p in range(pi, len(edges[v])):
                w = edges[v][p][1]
                if index[w] == -1:
                    work.append((v, p + 1))
                    work.append((w, 0))
                    advanced = True
                    break
                if on[w]:
                    low[v] = min(low[v], index[w])
            if advanced:
                continue
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on[w] = False
                    comp.append(w)
                    if w == v:
                        break
                out.append(comp)
            if work:
                u = work[-1][0]
                low[u] = min(low[u], low[v])
    return out
