"""The three events of a robot's cycle: Look (a snapshot of what it sees, in its own frame), Compute
(the algorithm's decision; its new light visible from here on) and Move (in the global frame, possibly
on a stale snapshot; collisions stop the run). A part the engine holds (:class:`Events`), acting on the
engine's state (:class:`~apf_viz.core.engine_core.EngineCore`)."""

from __future__ import annotations

from apf_viz.core.engine_core import EngineCore
from apf_viz.core.engine_state import COMPUTED, IDLE, LOOKED
from apf_viz.core.frames import move_to_global
from apf_viz.core.grid import Point
from apf_viz.core.history import Event

# Events are built with tuple.__new__: a NamedTuple's own __new__ (keywords, defaults) is a Python
# function and costs more than the rest of a no-op Move.
_new = tuple.__new__


class Events:
    """Look, Compute and Move of one robot (or, for a round's Moves, of several at once), on the state
    of ``core``: its positions and lights, its views and watches (told of every change), and the robots
    to decide anew."""

    def __init__(self, core: EngineCore) -> None:
        self.core = core

    def move_quietly(self, r: int, here: Point, to: Point, round: int | None) -> Event:
        """Robot r's pending move from ``here`` to ``to``, a free point, without telling the watches
        (:meth:`move_one` tells them of this move; fast-forward's forced cycles,
        :meth:`~apf_viz.core.walking.Walker._forced_cycles`, of the whole way, at its end)."""
        core = self.core
        st = core.state
        st.positions[r] = to
        core._views.moved((r,), (here,))
        st.moves += 1
        st.version += 1
        self._finish_cycle(r)
        return _new(Event, (r, "move", None, None, None, None, to, round, False, None))

    def look(self, r: int, round: int | None) -> Event:
        """Robot r's Look: a snapshot of what it sees, in its own frame, kept until its Compute."""
        core = self.core
        st = core.state
        snap, ids = core._observe(r)
        core._views.prime_seen_bits(r, ids)
        st.snapshot[r] = snap
        st.seen[r] = ids
        st.look_step[r] = st.steps + 1
        st.look_version[r] = st.version
        st.phase[r] = LOOKED
        return _new(Event, (r, "look", ids, None, None, None, None, round, False, None))

    def compute(self, r: int, round: int | None) -> Event:
        """Robot r's Compute on the snapshot of its Look: its decision is pending until its Move, and a new
        light is visible from here on (the watches are told)."""
        core = self.core
        st = core.state
        snap = st.snapshot[r]
        assert snap is not None
        decision = core._decide(r, snap)
        st.pending[r] = decision
        st.decided[r] = snap
        st.decided_seen[r] = st.seen[r]
        st.decided_look[r] = st.look_step[r]
        st.phase[r] = COMPUTED
        if decision.light != st.lights[r]:
            st.lights[r] = decision.light
            st.lights_used.add(decision.light)
            st.version += 1
            core._views.relit(r)
            # Always told, watched or not: it keeps every robot's light bit for later reveals.
            core._dirty.update(core._watches.relit(r, decision.light))
        gmove = move_to_global(decision.move, core.y_up[r])
        rule_id = decision.rule_id or None
        return _new(
            Event,
            (r, "compute", None, decision.light, gmove, decision.rule or None, None, round, False, rule_id),
        )

    def move(self, robots: tuple[int, ...], round: int | None) -> list[Event]:
        """Simultaneous moves of several robots (FSYNC/SSYNC); one robot goes to :meth:`move_one`."""
        core = self.core
        st = core.state
        targets: dict[int, Point] = {}
        for r in robots:
            decision = st.pending[r]
            assert decision is not None
            gmove = move_to_global(decision.move, core.y_up[r])
            x, y = st.positions[r].tolist()
            if gmove is None:
                targets[r] = (x, y)
            else:
                dx, dy = gmove.delta
                targets[r] = (x + dx, y + dy)
        collided = self._collisions(targets)
        events = [
            Event(robot=r, phase="move", to=targets[r], round=round, collision=r in collided) for r in robots
        ]
        if collided:
            st.outcome = "collision"
            return events
        here = {r: tuple(st.positions[r].tolist()) for r in robots}
        movers = [r for r in robots if targets[r] != here[r]]
        for r in movers:
            st.positions[r] = targets[r]
        if movers:
            core._views.moved(movers, [here[r] for r in movers])
            core._dirty.update(
                core._watches.moved(
                    [here[r] for r in movers], [targets[r] for r in movers], movers, core._views.occupied
                )
            )
            st.moves += len(movers)
            st.version += 1
        for r in robots:
            self._finish_cycle(r)
        return events

    def move_one(self, r: int, round: int | None) -> list[Event]:
        """The ASYNC case of :meth:`move`: one robot, so a collision is only a move onto a robot."""
        core = self.core
        st = core.state
        pending = st.pending[r]
        assert pending is not None  # computed: it holds its decision
        move = pending.move
        here = core._views.points[r]
        if move is None:
            self._finish_cycle(r)
            return [_new(Event, (r, "move", None, None, None, None, here, round, False, None))]
        dx, dy = move_to_global(move, core.y_up[r]).delta
        to = (here[0] + dx, here[1] + dy)
        if to in core._views.occupied:
            st.outcome = "collision"
            return [_new(Event, (r, "move", None, None, None, None, to, round, True, None))]
        event = self.move_quietly(r, here, to, round)
        core._dirty.update(core._watches.moved((here,), (to,), (r,), core._views.occupied))
        return [event]

    def _collisions(self, targets: dict[int, Point]) -> set[int]:
        """Robots whose simultaneous moves collide: shared target, a swap, or onto a robot that stays."""
        core = self.core
        st = core.state
        bad: set[int] = set()
        by_target: dict[Point, int] = {}
        for r, t in targets.items():
            if t in by_target:
                bad.update((r, by_target[t]))
            by_target[t] = r
        for r, t in targets.items():
            here = (int(st.positions[r][0]), int(st.positions[r][1]))
            if t == here:
                continue
            other = core._views.occupied.get(t)
            if other is None:
                continue
            if other not in targets or targets[other] == t:
                bad.update((r, other))  # onto a robot that is not leaving
            elif targets[other] == here:
                bad.update((r, other))  # swap across an edge
        return bad

    def _finish_cycle(self, r: int) -> None:
        core = self.core
        st = core.state
        decision = st.pending[r]
        assert decision is not None
        # A cycle that changed nothing on a still-current view proves this robot quiescent for now.
        if decision.move is None and st.look_version[r] == st.version:
            core._probe[r] = (st.version, True)
        st.phase[r] = IDLE
        st.pending[r] = None
        st.snapshot[r] = None
        st.seen[r] = None
        st.cycles += 1
        st.last_cycle_end[r] = st.steps + 1
