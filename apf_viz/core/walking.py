"""Fast-forward: a lone robot's cycles applied at once, exactly as the scheduler's forced choices would
apply them one by one (core/fast_forward.py holds the reasoning that bounds a walk; this is the engine's
part, :class:`Walker`, acting on its state, :class:`~apf_viz.core.engine_core.EngineCore`)."""

from __future__ import annotations

import numpy as np

from apf_viz.core.algorithm import Decision
from apf_viz.core.engine_core import EngineCore
from apf_viz.core.engine_state import IDLE
from apf_viz.core.events import Events
from apf_viz.core.fast_forward import (
    WalkMismatch,
    hidden_only_on_line,
    shifted,
    steps_in_same_sight,
    walk_mismatch,
)
from apf_viz.core.frames import move_to_global
from apf_viz.core.grid import COORD_LIMIT, Direction, Point
from apf_viz.core.history import Event, StepRecord, Walk
from apf_viz.core.quiet_steps import QuietSteps
from apf_viz.core.view import Snapshot

_MAX_WALK_WAIT = 63  # cycles between two tries of a walk that did not go (see Walker.walk)
# Cycles of a crowd's walker looked ahead for watches at once (Walker._forced_cycles): its decision
# usually changes sooner, and a look further ahead costs no more.
_FORCED_HORIZON = 256
_new = tuple.__new__  # events built without the NamedTuple's Python-level __new__


class Walker:
    """The engine's fast-forward (:meth:`walk`) and what it counts: a part the engine holds, acting on
    its state (``core``) through its events (``events``), as the steps it stands for would."""

    def __init__(self, core: EngineCore, events: Events) -> None:
        self.core = core
        self.events = events
        k = core.k
        self.walks = 0  # macro-steps applied by walk(), for benchmarks and tests
        self.broken_strides = 0  # strides whose last cycle decided otherwise (not walked), for tests
        self.forced_walks = 0  # runs of forced cycles applied by walk() (each cycle its own steps)
        # Per robot, cycles to let pass before trying a walk again, and the last such wait: in a crowd its
        # sight changes every few steps, and trying at every cycle would cost more than the walks save.
        self._walk_wait = [0] * k
        self._walk_backoff = [0] * k

    def walk(self, max_steps: int | None = None) -> int:
        """Apply the cycles of a lone robot at once: when it is the only robot whose next event can
        change anything (so a scheduler that serves the eligible robots has no choice), every other robot
        is watched, and its decision is a move that keeps its light. Where the decision promises a
        ``stride`` and the robot's sight stays the same, the cycles are one macro-step; else (a crowd)
        they are forced cycles, each Looked and decided anew (:meth:`_forced_cycles`). Either stops
        short of anything the other robots' watches, the budgets or ``max_steps`` would change
        (:mod:`apf_viz.core.fast_forward`). Returns the steps applied (0: none; the caller steps as
        usual)."""
        core = self.core
        st = core.state
        if not core.fast_forward or st.outcome is not None or core.history.length != st.steps:
            return 0
        eligible = core.eligible()
        if np.count_nonzero(eligible) != 1 or core._watches.count != core.k - 1:
            return 0
        r = int(eligible.nonzero()[0][0])
        if st.phase[r] != IDLE:
            return 0
        if self._walk_wait[r]:
            self._walk_wait[r] -= 1
            return 0
        snap, ids = core._observe(r)
        decision = core._decide(r, snap)
        if decision.move is None or decision.light != st.lights[r]:
            return 0
        per = 2 if core.light_semantics == "lc-atomic" else 3
        gmove = move_to_global(decision.move, core.y_up[r])
        delta = gmove.delta
        here = core._views.points[r]
        n = self._cycles_allowed(here, delta, per, max_steps)
        if n < 2:
            return 0  # a budget or the caller's limit: no reason to wait before the next try
        same = 0  # cycles that repeat this very decision on the same robots in sight
        if decision.stride >= 2 and hidden_only_on_line(st.positions, r, delta, snap.columns):
            same = steps_in_same_sight(snap.columns, decision.move, min(n, decision.stride))
            # The stride is the algorithm's promise; its last cycle is decided for real (one decision
            # on the view the walker will hold there), and a promise that fails there is not walked:
            # the cycles are then forced ones, each decided for real.
            if same >= 2 and core.decide(shifted(snap, decision.move, same - 1)) != decision:
                self.broken_strides += 1
                if core.check_walks:
                    raise WalkMismatch(
                        f"fast-forward: robot {r}'s stride of {decision.stride} on {decision.rule_id!r} is "
                        f"broken: its cycle {same} decides otherwise"
                    )
                same = 0
        # Else, in a crowd, cycles the scheduler cannot interleave, each Looked and decided anew.
        reach = same if same >= 2 else (min(n, _FORCED_HORIZON) if per == 3 else 0)
        if reach >= 2:
            reach = QuietSteps(core._watches).quiet_steps(r, here, delta, reach)
        if reach < 2:
            self._walk_wait[r] = self._walk_backoff[r] = min(2 * self._walk_backoff[r] + 1, _MAX_WALK_WAIT)
            return 0
        self._walk_backoff[r] = 0
        if same >= 2:
            self._walk(r, here, gmove, snap, ids, decision, reach, per)
            return reach * per
        return self._forced_cycles(r, here, gmove, reach)

    def _cycles_allowed(self, here: Point, delta: Point, per: int, max_steps: int | None) -> int:
        """The most cycles a walk from ``here`` by ``delta`` may take: within the budgets, the caller's
        ``max_steps``, and the coordinates where the sight test's arithmetic is exact (grid.COORD_LIMIT;
        beyond them the run goes on step by step)."""
        core = self.core
        st = core.state
        n = COORD_LIMIT - (here[0] * delta[0] + here[1] * delta[1])
        if core.max_events is not None:
            n = min(n, (core.max_events - st.events - 1) // 3)
        if core.max_moves is not None:
            n = min(n, core.max_moves - st.moves - 1)
        if max_steps is not None:
            n = min(n, max_steps // per)
        return n

    def _forced_cycles(self, r: int, here: Point, gmove: Direction, n: int) -> int:
        """Apply up to n whole cycles of robot r, each Look, Compute and Move recorded as its own step
        exactly as the scheduler's forced choices would be, while its decision keeps its light and its
        move (``gmove``, global): :meth:`walk` checked that those n moves concern no watcher and leave
        every budget, so r stays the only eligible robot and no outcome can fall inside. Other robots'
        watches are told of the whole way once at the end. Returns the steps applied (0: none)."""
        core = self.core
        st = core.state
        start = st.steps
        dx, dy = gmove.delta
        occupied = core._views.occupied
        light = st.lights[r]
        record = _new(StepRecord, ((r,), None))
        at = here
        cycles = 0
        while cycles < n:
            if cycles:
                decision = core._decide(r, core._observe(r)[0])
                if decision.light != light or move_to_global(decision.move, core.y_up[r]) != gmove:
                    break
            to = (at[0] + dx, at[1] + dy)
            if to in occupied:
                break  # a collision: stepped as usual
            self._forced_step(record, self.events.look(r, None))
            self._forced_step(record, self.events.compute(r, None))
            self._forced_step(record, self.events.move_quietly(r, at, to, None))
            at = to
            cycles += 1
        if not cycles:
            return 0
        if core.check_walks:
            self._check_walk(r, here, gmove, cycles, None)
        self.forced_walks += 1
        core._dirty.update(core._watches.moved((here,), (at,), (r,), occupied))
        core._dirty.add(r)
        core._update_outcome()
        core._checkpoint_after(start)
        return 3 * cycles

    def _check_walk(self, r: int, here: Point, gmove: Direction, n: int, decision: Decision | None) -> None:
        """``check_walks``: the n cycles of robot r from ``here`` are those the step-by-step run makes
        (:func:`~apf_viz.core.fast_forward.walk_mismatch`), or the run stops with the difference."""
        core = self.core
        positions = core.state.positions.copy()
        positions[r] = here
        problem = walk_mismatch(
            positions, core.state.lights, core.y_up, r, gmove.delta, n, decision, self._decide_afresh
        )
        if problem:
            raise WalkMismatch(f"fast-forward is not the step-by-step run: {problem}")

    def _decide_afresh(self, view: Snapshot) -> Decision:
        """The algorithm's decision, asked directly (no memo): the walk check's independent witness."""
        core = self.core
        return core.algorithm.decide(view, core.pattern)

    def _forced_step(self, record: StepRecord, event: Event) -> None:
        """The bookkeeping :meth:`apply` does around a step, for one of :meth:`_forced_cycles`' events
        (the robot already acted): the others skipped, its last act, the counts, the history."""
        core = self.core
        st = core.state
        st.skipped += core.k - 1
        st.last_act[event.robot] = st.steps + 1
        st.steps += 1
        st.events += 1
        core.history.record(st.steps - 1, record, [event])

    def _walk(
        self,
        r: int,
        here: Point,
        gmove: Direction,
        snap: Snapshot,
        ids: tuple[int, ...],
        decision: Decision,
        n: int,
        per: int,
    ) -> None:
        """Apply n cycles of robot r, from ``here`` by ``gmove`` (global), on this decision (:meth:`walk`
        checked that they repeat)."""
        core = self.core
        assert decision.move is not None  # a walk moves
        st = core.state
        if core.check_walks:
            self._check_walk(r, here, gmove, n, decision)
        dx, dy = gmove.delta
        to = (here[0] + n * dx, here[1] + n * dy)
        position = st.steps
        st.positions[r] = to
        core._views.moved((r,), (here,))
        core._dirty.update(core._watches.moved((here,), (to,), (r,), core._views.occupied))
        core._dirty.add(r)
        st.steps += n * per
        st.events += 3 * n
        st.moves += n
        st.cycles += n
        st.version += n
        st.skipped += (core.k - 1) * n * per
        last_look = st.steps - per + 1  # the step of the last cycle's Look (steps count from 1)
        st.look_step[r] = st.decided_look[r] = last_look
        st.look_version[r] = st.version - 1
        st.decided[r] = shifted(snap, decision.move, n - 1)
        st.decided_seen[r] = ids
        st.last_act[r] = st.last_cycle_end[r] = st.steps
        self.walks += 1
        look = _new(Event, (r, "look", ids, None, None, None, None, None, False, None))
        rule_id = decision.rule_id or None
        compute = _new(
            Event,
            (r, "compute", None, decision.light, gmove, decision.rule or None, None, None, False, rule_id),
        )
        core.history.record_walk(position, Walk.of(r, n * per, per, look, compute, here, (dx, dy)))
        core._update_outcome()
        core._checkpoint_after(position)
