"""A beam over the adversary's choices: the exact worst's state graph (explore/worst.py), searched a
layer at a time and cut to a width, for starts whose whole graph is out of reach.

The states are the explorer's (positions up to translation, lights, what each robot holds), its edges
the events a scheduler that skips no-ops may make, under ASYNC with the partial-order reduction
(docs/VERIFICATION.md): the same space on which ``check --worst`` finds the exact maximum. Layer d holds
the states d events from the start, each with the most moves (events) of any path found to it; the next
layer is their successors, and where it holds more than ``width`` states, ``width`` of them drawn at
random (seeded) are kept. A state none of whose robots can change anything ends its path: the costliest
such path is the answer, replayed in the real engine. A path that fails (a collision, an escape from
the box, a quiet state that is not the pattern) ends the beam: where a schedule fails there is no
maximum, and the failure, with its schedule, is the answer.

Why drawn at random rather than the costliest kept: a state that has made more moves by the same event
is, more often than not, one whose robots went straight to their places, and the runs that cost most
are the slow ones (on a k = 5 start whose exact worst is 60 moves, a beam keeping the costliest 64 found
46, one keeping 64 at random found 60). Where no layer is wider than ``width`` the beam is the whole
graph and its answer is the exact worst."""

from __future__ import annotations

import random
import time
from collections.abc import Callable
from dataclasses import dataclass

from apf_viz.algorithms import get_algorithm
from apf_viz.core.grid import as_point
from apf_viz.core.pattern_match import matches_pattern
from apf_viz.explore.explorer import Explorer
from apf_viz.explore.state_space import State
from apf_viz.explore.worst import Measure, edge_weight

MEMO_LIMIT = 400_000  # configurations whose decisions are remembered before the memo starts afresh


@dataclass
class Beamed:
    """What the beam found: the costliest path's value (None: no path it kept reached a quiet state),
    its schedule (robots per event), and its effort. ``cut``: a layer was cut to the width, or the paths
    to ``max_layers`` events, so the answer may be less than the exact worst. ``skipped``: edges that
    collide or leave the box, which no formed run takes."""

    value: int | None
    schedule: list[tuple[int, ...]]
    layers: int
    states: int
    cut: bool
    skipped: int
    seconds: float
    failure: tuple[str, list[tuple[int, ...]]] | None = None  # the first failure met: kind, schedule


Layer = dict[State, tuple[int, tuple[int, int], int]]  # state → (cost so far, origin, its node)


def beam(
    algorithm: str,
    robots,
    pattern,
    y_up,
    measure: Measure,
    width: int,
    seed: int = 0,
    light_semantics: str = "compute",
    progress: Callable[[int, int], None] = lambda layers, states: None,
    max_layers: int = 10_000_000,
) -> Beamed:
    """The beam of ``width`` from the start (see the module's words). ``progress(layers, states)`` is
    called every 100 layers; no path is followed past ``max_layers`` events. KeyboardInterrupt is the
    caller's: nothing is kept of a beam cut short."""
    t0 = time.perf_counter()
    if matches_pattern([as_point(p) for p in robots], [as_point(p) for p in pattern]):
        return Beamed(0, [], 0, 0, False, 0, time.perf_counter() - t0)  # formed before anyone acts (engine)
    explorer = Explorer(
        get_algorithm(algorithm), robots, pattern, y_up, scheduler="async", reduction=True,
        eligible_only=True, light_semantics=light_semantics,  # type: ignore[arg-type]
    )  # fmt: skip
    space = explorer.space
    rng = random.Random(seed)
    start, origin = space.initial(explorer.robots)
    paths = Paths()
    layer: Layer = {start: (0, origin, 0)}
    layers = states = skipped = 0
    cut = False
    while layer:
        if layers >= max_layers:  # a cycle the adversary may go round (a run's event budget, as the engine's)
            cut = True
            break
        following, expanded, violations = next_layer(explorer, layer, measure, paths)
        states += expanded
        skipped += violations
        if paths.failure is not None:  # no maximum where a schedule fails: the failure is the answer
            break
        if len(following) > width:
            cut = True
            kept = rng.sample(list(following), width)
            following = {s: following[s] for s in kept}
        layer = following
        layers += 1
        if layers % 100 == 0:
            progress(layers, states)
        if len(space.memo.by_configuration) > MEMO_LIMIT:  # a cache: the decisions' table stays
            space.forget()
    failure = None
    if paths.failure is not None:
        kind, node, group = paths.failure
        failure = (kind, paths.schedule(node) + ([group] if group else []))
    return Beamed(
        paths.best, paths.schedule(), layers, states, cut, skipped, time.perf_counter() - t0, failure
    )


class Paths:
    """The paths the beam has made, as a tree (each node its parent and the robots acting on its edge),
    and the costliest that ended."""

    def __init__(self) -> None:
        self.nodes: list[tuple[int, tuple[int, ...]]] = [(-1, ())]
        self.best: int | None = None
        self.best_node = 0
        self.failure: tuple[str, int, tuple[int, ...] | None] | None = None  # kind, node, the last edge

    def extend(self, node: int, group: tuple[int, ...]) -> int:
        self.nodes.append((node, group))
        return len(self.nodes) - 1

    def ended(self, cost: int, node: int) -> None:
        if self.best is None or cost > self.best:
            self.best, self.best_node = cost, node

    def failed(self, kind: str, node: int, group: tuple[int, ...] | None) -> None:
        if self.failure is None:
            self.failure = (kind, node, group)

    def schedule(self, node: int | None = None) -> list[tuple[int, ...]]:
        """The robots acting on each event of the path to ``node`` (the costliest that ended), first to
        last."""
        out: list[tuple[int, ...]] = []
        node = self.best_node if node is None else node
        while node > 0:
            node, group = self.nodes[node]
            out.append(group)
        return out[::-1]


def next_layer(explorer: Explorer, layer: Layer, measure: Measure, paths: Paths) -> tuple[Layer, int, int]:
    """The states one event after ``layer``'s, each with the costliest path to it (a state where nobody
    can change anything ends its path instead); and the states expanded, and the edges skipped because
    they collide or leave the box."""
    space = explorer.space
    following: Layer = {}
    expanded = skipped = 0
    for st, (cost, at, node) in layer.items():
        if space.quiescent(st):
            if not matches_pattern(space.positions(st, at), explorer.pattern):
                paths.failed("deadlock", node, None)  # quiet, and not the pattern
            paths.ended(cost, node)
            continue
        expanded += 1
        out: list[tuple[State, tuple[int, int]]] = []
        groups, violation = explorer.eligible_edges(st, at, out)
        if violation is not None:
            skipped += 1
            if str(violation).startswith("collision"):  # an escape only leaves the box: no verdict
                paths.failed("collision", node, violation.robots)
        for group, (nxt, there) in zip(groups, out, strict=True):
            value = cost + edge_weight(space, st, group, measure, nxt)
            held = following.get(nxt)
            if held is None or value > held[0]:
                following[nxt] = (value, there, paths.extend(node, group))
    return following, expanded, skipped
