"""The three events of a robot's cycle: Look (a snapshot of what it sees, in its own frame), Compute
(the algorithm's decision; its new light visible from here on) and Move (in the global frame, possibly
on a stale snapshot; collisions stop the run). A mixin of :class:`~apf_viz.core.engine.Engine`, which it
needs these of (declared for the type checker only)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from apf_viz.core.algorithm import Decision
from apf_viz.core.engine_state import COMPUTED, IDLE, LOOKED, EngineState
from apf_viz.core.frames import move_to_global
from apf_viz.core.grid import Point
from apf_viz.core.history import Event
from apf_viz.core.view import Snapshot

if TYPE_CHECKING:
    from apf_viz.core.visibility import Views
    from apf_viz.core.watches import Watches

# Plain ints on the hot path: attribute access on an Enum class costs more than the rest of a step.
# Events are built with tuple.__new__: a NamedTuple's own __new__ (keywords, defaults) is a Python
# function and costs more than the rest of a no-op Move.
_new = tuple.__new__


class Events:
    """Look, Compute and Move of one robot (or, for a round's Moves, of several at once)."""

    if TYPE_CHECKING:  # the engine's, read here
        state: EngineState
        y_up: tuple[bool, ...]
        _views: Views
        _watches: Watches
        _dirty: set[int]
        _snaps: list[tuple[object, Snapshot] | None]
        _probe: list[tuple[int, bool]]

        def _decide(self, r: int, view: Snapshot) -> Decision: ...

    def _move_quietly(self, r: int, here: Point, to: Point, round: int | None) -> Event:
        """Robot r's pending move from ``here`` to ``to``, a free point, without telling the watches
        (:meth:`_move_one` tells them of this move; :meth:`_forced_cycles` of the whole way, at its
        end)."""
        st = self.state
        st.positions[r] = to
        self._views.moved((r,), (here,))
        st.moves += 1
        st.version += 1
        self._finish_cycle(r)
        return _new(Event, (r, "move", None, None, None, None, to, round, False, None))

    def _look(self, r: int, round: int | None) -> Event:
        st = self.state
        snap, ids = self._observe(r)
        self._views.prime_seen_bits(r, ids)
        st.snapshot[r] = snap
        st.seen[r] = ids
        st.look_step[r] = st.steps + 1
        st.look_version[r] = st.version
        st.phase[r] = LOOKED
        return _new(Event, (r, "look", ids, None, None, None, None, round, False, None))

    def _observe(self, r: int) -> tuple[Snapshot, tuple[int, ...]]:
        """Robot r's snapshot and the sorted indices of the robots in it, read off the patched views."""
        snap = self._snapshot(r)
        return snap, self._views.view(r)[1]

    def _snapshot(self, r: int) -> Snapshot:
        """Robot r's snapshot (entries sorted by offset in r's own frame: a canonical, identity-free
        order); the same object while its view and light are unchanged."""
        robots = self._views.robots(r)
        light = self.state.lights[r]
        held = self._snaps[r]
        if held is not None and held[0] is robots and held[1].light == light:
            return held[1]
        snap = Snapshot(light, robots) if isinstance(robots, tuple) else Snapshot(light, columns=robots)
        self._snaps[r] = (robots, snap)
        return snap

    def _compute(self, r: int, round: int | None) -> Event:
        st = self.state
        snap = st.snapshot[r]
        assert snap is not None
        decision = self._decide(r, snap)
        st.pending[r] = decision
        st.decided[r] = snap
        st.decided_seen[r] = st.seen[r]
        st.decided_look[r] = st.look_step[r]
        st.phase[r] = COMPUTED
        if decision.light != st.lights[r]:
            st.lights[r] = decision.light
            st.lights_used.add(decision.light)
            st.version += 1
            self._views.relit(r)
            # Always told, watched or not: it keeps every robot's light bit for later reveals.
            self._dirty.update(self._watches.relit(r, decision.light))
        gmove = move_to_global(decision.move, self.y_up[r])
        rule_id = decision.rule_id or None
        return _new(
            Event,
            (r, "compute", None, decision.light, gmove, decision.rule or None, None, round, False, rule_id),
        )

    def _move(self, robots: tuple[int, ...], round: int | None) -> list[Event]:
        """Simultaneous moves of several robots (FSYNC/SSYNC); one robot goes to :meth:`_move_one`."""
        st = self.state
        targets: dict[int, Point] = {}
        for r in robots:
            decision = st.pending[r]
            assert decision is not None
            gmove = move_to_global(decision.move, self.y_up[r])
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
            self._views.moved(movers, [here[r] for r in movers])
            self._dirty.update(
                self._watches.moved(
                    [here[r] for r in movers], [targets[r] for r in movers], movers, self._views.occupied
                )
            )
            st.moves += len(movers)
            st.version += 1
        for r in robots:
            self._finish_cycle(r)
        return events

    def _move_one(self, r: int, round: int | None) -> list[Event]:
        """The ASYNC case of :meth:`_move`: one robot, so a collision is only a move onto a robot."""
        st = self.state
        pending = st.pending[r]
        assert pending is not None  # computed: it holds its decision
        move = pending.move
        here = self._views.points[r]
        if move is None:
            self._finish_cycle(r)
            return [_new(Event, (r, "move", None, None, None, None, here, round, False, None))]
        dx, dy = move_to_global(move, self.y_up[r]).delta
        to = (here[0] + dx, here[1] + dy)
        if to in self._views.occupied:
            st.outcome = "collision"
            return [_new(Event, (r, "move", None, None, None, None, to, round, True, None))]
        event = self._move_quietly(r, here, to, round)
        self._dirty.update(self._watches.moved((here,), (to,), (r,), self._views.occupied))
        return [event]

    def _collisions(self, targets: dict[int, Point]) -> set[int]:
        """Robots whose simultaneous moves collide: shared target, a swap, or onto a robot that stays."""
        st = self.state
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
            other = self._views.occupied.get(t)
            if other is None:
                continue
            if other not in targets or targets[other] == t:
                bad.update((r, other))  # onto a robot that is not leaving
            elif targets[other] == here:
                bad.update((r, other))  # swap across an edge
        return bad

    def _finish_cycle(self, r: int) -> None:
        st = self.state
        decision = st.pending[r]
        assert decision is not None
        # A cycle that changed nothing on a still-current view proves this robot quiescent for now.
        if decision.move is None and st.look_version[r] == st.version:
            self._probe[r] = (st.version, True)
        st.phase[r] = IDLE
        st.pending[r] = None
        st.snapshot[r] = None
        st.seen[r] = None
        st.cycles += 1
        st.last_cycle_end[r] = st.steps + 1
