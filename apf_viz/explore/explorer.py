"""Exhaustive schedule exploration: every execution the adversary can produce from a small start.

The states and transitions are :mod:`apf_viz.explore.state_space`'s. ASYNC: from a state each robot's
next event is one transition (k successors). SSYNC: each non-empty set of robots runs one atomic cycle
(Looks, then Computes, then simultaneous Moves). FSYNC: everyone.

Verdicts: ``collision``; ``escape`` (a robot left the box around start ∪ pattern, so the search is not
finite); ``deadlock`` (a terminal state that is not the pattern); ``livelock`` (a strongly connected set of
states, not all quiescent, in which every robot acts: a fair execution that never ends); ``budget`` (the
state limit was hit first: nothing is proved); ``verified``.

``want`` looks for one kind of failure only: a violation of another kind ends that run (its edge leads
nowhere) and the search goes on past it, so a deadlock is found where a collision would have stopped
the search first. None of that kind in the whole space is verdict ``absent`` (what was passed over is
counted in the detail).
"""

from __future__ import annotations

import gc
import time
from collections import deque
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from itertools import combinations
from typing import Literal

from apf_viz.core.algorithm import Algorithm
from apf_viz.core.grid import Point, as_point
from apf_viz.core.pattern_match import matches_pattern
from apf_viz.explore.state_space import Decisions, State, StateSpace, Violation

__all__ = ["WANTED", "Decisions", "Explorer", "Result", "Verdict", "Wanted"]

Verdict = Literal["verified", "collision", "escape", "deadlock", "livelock", "budget", "absent"]
Wanted = Literal["collision", "escape", "deadlock", "livelock"]
WANTED: tuple[Wanted, ...] = ("collision", "escape", "deadlock", "livelock")


PROGRESS_EVERY = 5.0  # seconds: the longest a search is silent, however slow its states


@dataclass
class Result:
    verdict: Verdict
    states: int
    transitions: int
    seconds: float
    schedule: list[tuple[int, ...]] = field(default_factory=list)  # robots per step, from the start
    loop_start: int | None = None  # for a livelock: the step index where the repeated part begins
    detail: str = ""
    passed: dict[str, int] = field(default_factory=dict)  # ``want``: failures of other kinds passed over


@dataclass
class Graph:
    """The searched graph: states by index, each one's origin, the state and robots it was first reached
    from, and its edges (target indices, labelled by the robots acting, ``labels[i][p]`` for
    ``edges[i][p]``)."""

    states: list[State]
    origins: list[Point]
    parent: list[int] = field(default_factory=lambda: [-1])
    via: list[tuple[int, ...]] = field(default_factory=lambda: [()])
    edges: list[list[int]] = field(default_factory=list)
    labels: list[tuple[tuple[int, ...], ...]] = field(default_factory=list)
    transitions: int = 0

    def path(self, i: int) -> list[tuple[int, ...]]:
        """The robots of each step from the start to state i (the breadth-first tree's: a shortest)."""
        steps = []
        while self.parent[i] >= 0:
            steps.append(self.via[i])
            i = self.parent[i]
        return steps[::-1]


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
        want: Wanted | None = None,
        eligible_only: bool = False,
    ) -> None:
        self.algorithm = algorithm
        self.want = want
        # Only the activations a scheduler that skips no-ops makes (explore/worst.py counts events so).
        self.eligible_only = eligible_only
        self.passed: dict[str, int] = {}  # with ``want``: the failures of other kinds passed over
        self.graph: Graph | None = None  # once :meth:`run` has searched the whole space
        self.robots = [as_point(p) for p in robots]
        self.pattern = tuple(as_point(p) for p in pattern)
        self.y_up = tuple(y_up)
        self.k = len(self.robots)
        self.scheduler = scheduler
        self.max_states = max_states
        self.progress = progress
        pts = self.robots + list(self.pattern)
        span = max(
            max(p[0] for p in pts) - min(p[0] for p in pts), max(p[1] for p in pts) - min(p[1] for p in pts)
        )
        # The paper's moves stay within O(kD) of the start; a box this much wider than start ∪ pattern is
        # generous for the starts the explorer can handle, and keeps the state space finite.
        self.margin = margin if margin is not None else 2 * (self.k + span) + 4
        box = (
            min(p[0] for p in self.robots) - self.margin,
            min(p[1] for p in self.robots) - self.margin,
            max(p[0] for p in self.robots) + self.margin,
            max(p[1] for p in self.robots) + self.margin,
        )
        self.space = StateSpace(
            algorithm,
            self.pattern,
            self.y_up,
            scheduler,
            light_semantics == "lc-atomic",
            # Partial-order reduction (docs/VERIFICATION.md): only under ASYNC, where one event is one
            # robot's.
            reduction and scheduler == "async" and want is None,  # its argument is for the whole verdict
            # Shared by the searches of one start under several flips (explore/check.py), or this one's own.
            decisions if decisions is not None else Decisions(),
            box,
        )

    def initial(self) -> State:
        return self.space.initial(self.robots)[0]

    def successors(self, st: State, origin: Point = (0, 0)) -> list[tuple[tuple[int, ...], State | str]]:
        """(robots acting, next state) pairs; a violation is a string instead of a state."""
        out: list[tuple[State, Point]] = []
        try:
            groups = self.space.successors(st, origin, out)
        except Violation as v:
            return [(g, n[0]) for g, n in zip(self.space.labels, out, strict=False)] + [(v.robots, str(v))]
        return [(g, n[0]) for g, n in zip(groups, out, strict=True)]

    # ------------------------------------------------------------------ search
    def run(self) -> Result:
        """The verdict: every reachable state searched (breadth first), then the terminal states that are
        not the pattern (deadlocks) and the fair cycles that never become quiescent (livelocks)."""
        t0 = time.perf_counter()
        if matches_pattern(self.robots, self.pattern):  # the engine's rule: formed before anyone acts
            return Result("verified", 1, 0, 0.0, detail="the start is already the pattern: formed at time 0")
        with _no_cyclic_gc():
            graph = self._search(t0)
        if isinstance(graph, Result):
            return graph  # a collision, an escape, or the state budget
        self.graph = graph  # every state searched and its edges: explore/worst.py reads them
        n = len(graph.states)
        quiet = [self.space.quiescent(s) for s in graph.states]
        for i, s in enumerate(graph.states):
            if quiet[i] and not matches_pattern(self.space.positions(s, graph.origins[i]), self.pattern):
                if self.want in (None, "deadlock"):
                    detail = "a terminal state that is not the pattern"
                    return self._fail("deadlock", detail, graph, i, None, t0)
                self.passed["deadlock"] = self.passed.get("deadlock", 0) + 1
        if self.want in ("collision", "escape", "deadlock"):
            return self._absent(graph, t0)
        loop = self._fair_cycle(graph, quiet)
        seconds = time.perf_counter() - t0
        if loop is not None:
            entry, cycle = loop
            stem = graph.path(entry)
            return Result(
                "livelock",
                n,
                graph.transitions,
                seconds,
                stem + cycle,
                loop_start=len(stem),
                detail="a fair cycle of states that never becomes quiescent",
            )
        if self.want is not None:
            return self._absent(graph, t0)
        return Result("verified", n, graph.transitions, seconds)

    def _absent(self, graph: Graph, t0: float) -> Result:
        """No failure of the kind wanted anywhere in the space searched (within the box)."""
        assert self.want is not None
        seconds = time.perf_counter() - t0
        detail = absent_detail(self.want, self.passed)
        return Result(
            "absent", len(graph.states), graph.transitions, seconds, detail=detail, passed=self.passed
        )

    def eligible_edges(
        self, st: State, origin: Point, out: list[tuple[State, Point]]
    ) -> tuple[tuple[tuple[int, ...], ...], Violation | None]:
        """The edges out of ``st`` a scheduler that skips no-ops may take, each on its own (see
        :meth:`_careful_successors`): for a search of its own over this space (explore/beam.py)."""
        return self._careful_successors(st, origin, out)

    def _careful_successors(
        self, st: State, origin: Point, out: list[tuple[State, Point]]
    ) -> tuple[tuple[tuple[int, ...], ...], Violation | None]:
        """Each edge on its own: only the eligible robots' with ``eligible_only``; with ``want``, a
        violation of another kind is counted and leads nowhere. Returns the edges' labels and the
        violation that stops the search (the edges before it are in ``out``), if any."""
        space = self.space
        groups: list[tuple[int, ...]] = []
        for g in self._candidates(st):
            try:
                out.append(space.edge(st, origin, g))
            except Violation as v:
                kind = "collision" if str(v).startswith("collision") else "escape"
                if self.want is None or kind == self.want:
                    return tuple(groups), v
                self.passed[kind] = self.passed.get(kind, 0) + 1
                continue
            groups.append(g)
        return tuple(groups), None

    def _candidates(self, st: State) -> tuple[tuple[int, ...], ...]:
        """The robots that may act on each edge out of ``st``."""
        space = self.space
        if not self.eligible_only:
            return space.labels
        movers = space.eligible(st)
        if space.scheduler == "async":
            if space.reduction:
                r = space.invisible(st)
                if r is not None and r in movers:  # alone, as the reduction explores it (an ample set)
                    return (space.singles[r],)
            return tuple(space.singles[r] for r in movers)
        if not movers:
            return ()
        if space.scheduler == "fsync":
            return (tuple(movers),)
        return tuple(c for n in range(1, len(movers) + 1) for c in combinations(movers, n))

    def _search(self, t0: float) -> Result | Graph:
        """Every state reachable from the start, breadth first, or the Result that stopped the search (a
        collision, an escape past the coordinates, the budget)."""
        start, origin = self.space.initial(self.robots)
        graph = Graph([start], [origin])
        states, origins, parent, via = graph.states, graph.origins, graph.parent, graph.via
        edges, labels = graph.edges, graph.labels
        index: dict[State, int] = {start: 0}
        successors = self.space.successors
        before = self.space.labels  # what the edges before a violation are labelled by
        i = -1  # breadth first: states are searched in the order they are found, so an index is the queue
        said = t0  # when progress was last reported
        while i + 1 < len(states):
            i += 1
            nexts: list[tuple[State, Point]] = []
            violation = None
            if self.want is not None or self.eligible_only:
                groups, violation = self._careful_successors(states[i], origins[i], nexts)
            else:
                try:
                    groups = successors(states[i], origins[i], nexts)
                except Violation as v:
                    groups, violation = before, v  # the edges before it are searched first, as any edges
            out: list[int] = []
            for p, (st, o) in enumerate(nexts):
                j = index.get(st)
                if j is None:
                    if len(states) >= self.max_states:
                        graph.transitions += p + 1
                        detail = f"stopped at {self.max_states} states: nothing is proved"
                        return Result(
                            "budget", len(states), graph.transitions, time.perf_counter() - t0, detail=detail
                        )
                    j = index[st] = len(states)
                    states.append(st)
                    origins.append(o)
                    parent.append(i)
                    via.append(groups[p])
                    if self.want == "deadlock" and self._deadlocked(st, o):  # the goal: said at once
                        return self._fail(
                            "deadlock", "a terminal state that is not the pattern", graph, j, None, t0
                        )
                out.append(j)
            graph.transitions += len(out)
            if violation is not None:
                graph.transitions += 1
                message = str(violation)
                verdict = "collision" if message.startswith("collision") else "escape"
                return self._fail(verdict, message, graph, i, violation.robots, t0)
            edges.append(out)
            labels.append(groups)
            # Every 20,000 states, or every few seconds where states are slow (robots far apart).
            if self.progress and (len(edges) % 20_000 == 0 or time.perf_counter() - said > PROGRESS_EVERY):
                said = time.perf_counter()
                self.progress(len(states), len(states) - i - 1, said - t0)
        return graph

    def _deadlocked(self, st: State, origin: Point) -> bool:
        """Quiet (nobody can change anything) and not the pattern."""
        return self.space.quiescent(st) and not matches_pattern(
            self.space.positions(st, origin), self.pattern
        )

    def _fail(self, verdict, detail, graph: Graph, i: int, robots, t0: float) -> Result:
        schedule = graph.path(i) + ([robots] if robots is not None else [])
        seconds = time.perf_counter() - t0
        return Result(verdict, len(graph.states), graph.transitions, seconds, schedule, detail=detail)

    def _fair_cycle(self, graph: Graph, quiet: list[bool]) -> tuple[int, list[tuple[int, ...]]] | None:
        """A strongly connected component, not all quiescent, with an edge of every robot inside it;
        returned as (entry state, a cycle from it that lets every robot act)."""
        edges, labels = graph.edges, graph.labels
        for comp in _sccs(edges):
            if len(comp) == 1 and comp[0] not in edges[comp[0]]:
                continue  # no cycle through it
            if all(quiet[i] for i in comp):
                continue
            members = set(comp)
            actors = {r for i in comp for p, j in enumerate(edges[i]) if j in members for r in labels[i][p]}
            if self.eligible_only:  # a robot left out where it would change nothing acts there: a no-op
                actors |= {r for i in comp for r in self._idle_noops(graph.states[i])}
            if actors != set(range(self.k)):
                continue
            entry = min(comp)
            return entry, self._tour(entry, members, graph)
        return None

    @staticmethod
    def _acts_inside(r: int, members: set[int], graph: Graph) -> bool:
        return any(
            r in robots
            for i in members
            for p, robots in enumerate(graph.labels[i])
            if graph.edges[i][p] in members
        )

    def _idle_noops(self, st: State) -> set[int]:
        """The robots a search of eligible activations leaves out in ``st``: idle, and a whole cycle of
        theirs there would change nothing (it returns to ``st``: a fair run may take it at any time)."""
        return set(range(self.k)) - set(self.space.eligible(st))

    def _tour(self, entry: int, members: set[int], graph: Graph) -> list[tuple[int, ...]]:
        """Inside one component: from ``entry``, take an edge of every robot in turn, then come back (a
        robot whose activations there are no-ops, left out of the graph, acts where it is one)."""
        path: list[tuple[int, ...]] = []
        here = entry
        for r in range(self.k):
            if self.eligible_only and not self._acts_inside(r, members, graph):
                # Its cycles inside are no-ops (left out of the graph): one of them, where it is one.
                noop = min(i for i in members if r in self._idle_noops(graph.states[i]))
                steps, here = _bfs(here, members, graph, None, target=noop)
                path += steps + [self.space.singles[r]] * 3  # its Look, Compute and Move
                continue
            steps, here = _bfs(here, members, graph, lambda robots, r=r: r in robots)
            path += steps
        steps, here = _bfs(here, members, graph, None, target=entry)
        return path + steps


@contextmanager
def _no_cyclic_gc() -> Iterator[None]:
    """Python's cyclic collector off while the search grows its graph: the states are flat tuples of
    integers, which make no cycles, yet each full collection walks all of them (a fifth of a search's
    time at k = 20–30: docs/PERFORMANCE.md, "The hunt"). Restored afterwards."""
    was = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was:
            gc.enable()


def absent_detail(want: str, passed: dict[str, int]) -> str:
    """What an "absent" verdict says: none of the kind wanted, and the other failures passed over."""
    detail = f"no {want} in any schedule (every state within the box searched)"
    if passed:
        detail += "; passed over: " + ", ".join(f"{n:,} {kind}(s)" for kind, n in sorted(passed.items()))
    return detail


def _bfs(src, members, graph: Graph, want, target=None):
    """Shortest path inside ``members`` ending with an edge satisfying ``want`` (or at ``target``)."""
    if target is not None and src == target:
        return [], src
    prev: dict[int, tuple[int, tuple[int, ...]] | None] = {src: None}  # node → (node before, edge)

    def steps_to(node: int, last: list) -> list[tuple[int, ...]]:
        steps = last
        while (back := prev[node]) is not None:
            node, rb = back
            steps.append(rb)
        return steps[::-1]

    queue = deque([src])
    while queue:
        i = queue.popleft()
        for p, j in enumerate(graph.edges[i]):
            if j not in members:
                continue
            robots = graph.labels[i][p]
            if want is not None and want(robots):
                return steps_to(i, [robots]), j
            if j not in prev:
                prev[j] = (i, robots)
                if target is not None and j == target:
                    return steps_to(j, []), j
                queue.append(j)
    raise AssertionError("component is not strongly connected")


def _sccs(edges: list[list[int]]) -> list[list[int]]:
    """Tarjan's algorithm, iterative (each frame resumes its own iterator over its edges)."""
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
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on[root] = True
        work = [(root, iter(edges[root]))]
        while work:
            v, it = work[-1]
            for w in it:
                if index[w] == -1:
                    index[w] = low[w] = counter
                    counter += 1
                    stack.append(w)
                    on[w] = True
                    work.append((w, iter(edges[w])))
                    break
                if on[w] and index[w] < low[v]:
                    low[v] = index[w]
            else:
                work.pop()
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
                    if low[v] < low[u]:
                        low[u] = low[v]
    return out
