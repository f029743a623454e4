"""The adversary's best play on a small start, exactly: the most moves (or events) any schedule and
flip assignment can force before the pattern forms, and one schedule that forces it.

The state graph is :class:`~apf_viz.explore.explorer.Explorer`'s, restricted to the activations a
scheduler that skips no-ops makes (the engine's ``eligible``: a whole cycle that changes nothing is no
event; otherwise an adversary could add such cycles without end, and no maximum would exist). A start
the plain search does not verify has no maximum: its verdict (collision, deadlock, livelock, escape,
budget) is the answer. On a verified graph every run ends formed; the most an adversary can force is
the longest path from the start to a quiescent state, each edge weighed by the moves (robots whose
point changed) or the events it makes. A cycle of the graph that makes moves (for events: any cycle)
can be gone round as often as the adversary likes before it lets the run go on, so such a start has no
maximum either (it is said, with the cycle's length), although no fair run is endless.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Literal

from apf_viz.core.algorithm import Algorithm
from apf_viz.core.grid import Point
from apf_viz.explore.explorer import Decisions, Explorer, Graph, Result, _sccs
from apf_viz.explore.state_space import State, StateSpace

Measure = Literal["moves", "events"]
MEASURES: tuple[Measure, ...] = ("moves", "events")


@dataclass
class Worst:
    """The answer for one start: the maximum (None where there is none), what stands instead of it
    (``verdict``: "worst", "unbounded", or the plain search's failure), the schedule forcing it (robots
    per step, as the explorer's), the flips it needs, and the effort."""

    measure: Measure
    verdict: str
    value: int | None
    y_up: tuple[bool, ...]
    states: int
    seconds: float
    schedule: list[tuple[int, ...]] = field(default_factory=list)
    detail: str = ""


def weights(explorer: Explorer, graph: Graph, measure: Measure) -> list[list[int]]:
    """Each edge's weight (:func:`edge_weight`), per state, per edge."""
    space = explorer.space
    return [
        [
            edge_weight(space, graph.states[i], graph.labels[i][p], measure, graph.states[j])
            for p, j in enumerate(targets)
        ]
        for i, targets in enumerate(graph.edges)
    ]


def edge_weight(
    space: StateSpace, st: State, group: tuple[int, ...], measure: Measure, target: State | None = None
) -> int:
    """What the edge out of ``st`` on which ``group`` acts costs: the robots it moves (read from the
    decisions, not from the states: a state is kept up to translation, so two states' points need not
    share an origin), or the events it makes (a round: Look, Compute and Move of each robot in it; an
    lc-atomic Look brings its Compute). A round that moves nobody and leaves every robot quiet (its
    ``target``) ends the run after its Computes, as the engine does (the new lights are the last change):
    its Moves, which would all stay, are never made."""
    k = space.k
    moves_of = space.memo.moves
    if measure == "moves" and space.scheduler == "async":
        code = st[3 * k + group[0]]  # a Move: its robot has Computed (an even code past 0)
        return 1 if code and not code & 1 and moves_of[space.y_up[group[0]]][(code - 1) >> 1] else 0
    if measure == "moves":  # a round: each robot moves as it decides on the state's view
        cfg = st[: 3 * k]
        return sum(1 for r in group if moves_of[space.y_up[r]][space.decide(cfg, r)])
    if space.scheduler == "async":
        return 2 if st[3 * k + group[0]] == 0 and space.lc_atomic else 1
    if target is not None and space.quiescent(target):
        cfg = st[: 3 * k]
        if not any(moves_of[space.y_up[r]][space.decide(cfg, r)] for r in group):
            return 2 * len(group)
    return 3 * len(group)


def longest(
    graph: Graph, weight: list[list[int]], sinks: Sequence[bool]
) -> tuple[int, list[tuple[int, ...]]] | tuple[None, int]:
    """The heaviest path from state 0 to a sink (a quiescent state: nothing follows it), and its
    schedule; or (None, states) when a cycle of positive weight is reachable (the states of its
    strongly connected set). A cycle of weight 0 costs nothing: each of its states is worth its best
    way out."""
    n = len(graph.edges)
    edges = [[] if sinks[i] else graph.edges[i] for i in range(n)]
    best = [0] * n
    choice = [-1] * n  # the edge each state takes on the heaviest path
    for members in _sccs(edges):  # sinks first: a component after every component it reaches
        inside = set(members)
        internal = [(v, p) for v in members for p, w in enumerate(edges[v]) if w in inside]
        if any(weight[v][p] > 0 for v, p in internal):
            return None, len(members)
        exits = [(weight[v][p] + best[edges[v][p]], v, p) for v in members for p, w in enumerate(edges[v])
                 if w not in inside]  # fmt: skip
        if not exits:
            continue  # a sink: worth 0, nothing follows
        value, door, p = max(exits)
        for v, hop in _routes_to(door, members, edges).items():
            best[v], choice[v] = value, hop
        choice[door] = p
    path, v = [], 0
    while choice[v] != -1:
        p = choice[v]
        path.append(graph.labels[v][p])
        v = edges[v][p]
    return best[0], path


def _routes_to(door: int, members: list[int], edges: list[list[int]]) -> dict[int, int]:
    """Inside one strongly connected set: for each state, the edge that leads towards ``door`` (a
    breadth-first tree over the reversed edges); ``door`` itself included (its edge set by the caller)."""
    inside = set(members)
    into: dict[int, list[tuple[int, int]]] = {v: [] for v in members}
    for v in members:
        for p, w in enumerate(edges[v]):
            if w in inside:
                into[w].append((v, p))
    hop = {door: -1}
    frontier = [door]
    while frontier:
        nxt = []
        for w in frontier:
            for v, p in into[w]:
                if v not in hop:
                    hop[v] = p
                    nxt.append(v)
        frontier = nxt
    return hop


def worst(
    algorithm: Algorithm,
    robots: Sequence[Point],
    pattern: Sequence[Point],
    flips: Sequence[Sequence[bool]],
    measure: Measure,
    *,
    scheduler: str = "async",
    max_states: int = 1_000_000,
    reduction: bool = True,
    light_semantics: str = "compute",
    progress: Callable[[int, int, float], None] | None = None,
) -> Worst:
    """The most ``measure`` any adversary can force before FORMED, over every schedule and each of
    ``flips``; or the reason there is no maximum."""
    t0 = time.perf_counter()
    total = 0
    found: Worst | None = None
    decisions = Decisions()
    for y_up in flips:
        explorer = Explorer(
            algorithm, robots, pattern, y_up,
            scheduler=scheduler,  # type: ignore[arg-type]
            max_states=max(1, max_states - total),
            light_semantics=light_semantics,  # type: ignore[arg-type]
            reduction=reduction,
            decisions=decisions,
            eligible_only=True,
            progress=progress,
        )  # fmt: skip
        verdict = explorer.run()  # the plain verdict first: a failure has no maximum
        total += verdict.states
        if verdict.verdict != "verified":
            return _failed(measure, verdict, tuple(y_up), total, t0)
        graph = explorer.graph
        path: list[tuple[int, ...]] = []
        value = 0  # formed before anyone acts (no graph): nothing to force
        if graph is not None:
            sinks = [explorer.space.quiescent(s) for s in graph.states]
            heaviest = longest(graph, weights(explorer, graph, measure), sinks)
            if heaviest[0] is None:
                return Worst(
                    measure, "unbounded", None, tuple(y_up), total, time.perf_counter() - t0,
                    detail=f"a cycle through {heaviest[1]} states that makes {measure} can be gone round "
                    "as often as the adversary likes before the run goes on (no fair run is endless)",
                )  # fmt: skip
            value, path = heaviest[0], list(heaviest[1])
        if found is None or found.value is None or value > found.value:
            found = Worst(measure, "worst", value, tuple(y_up), 0, 0.0, list(path))
    assert found is not None
    found.states, found.seconds = total, time.perf_counter() - t0
    return found


def _failed(measure: Measure, result: Result, y_up: tuple[bool, ...], states: int, t0: float) -> Worst:
    return Worst(
        measure, result.verdict, None, y_up, states, time.perf_counter() - t0, list(result.schedule),
        detail=f"no maximum: {result.detail or result.verdict}",
    )  # fmt: skip


def worst_schedule_text(
    algorithm: Algorithm, robots, pattern, found: Worst, scheduler: str, light_semantics: str = "compute"
) -> tuple[str, int, int]:
    """The schedule that forces the worst as a schedule file (its flips in the header), replayed in the
    real engine: (the file, the moves, the events) the replay counted."""
    from apf_viz.core.schedule import Found, schedule_of_steps, schedule_text
    from apf_viz.explore.check import counterexample_engine

    result = Result("verified", found.states, 0, found.seconds, found.schedule)
    e = counterexample_engine(algorithm, robots, pattern, found.y_up, scheduler, result, light_semantics)
    # Its header says what it is (the page's Load the worst found shows it, with moves per k·D).
    said = Found(maximize=found.measure, value=found.value or 0, by="check", states=found.states)
    text = schedule_text(e.k, schedule_of_steps(e.history.steps), e.y_up, e.light_semantics, said)
    return text, e.state.moves, e.state.events
