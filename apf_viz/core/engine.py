"""The Look-Compute-Move engine: robot phases, one step of events at a time, outcomes, time travel.

Each robot cycles idle → looked (holds its snapshot) → computed (its new light is visible from this
event on, it holds a pending move) → idle after its Move. A robot therefore has exactly one enabled event
at any time, and a scheduler chooses *robots*, never phases: the engine, not the scheduler and not the
algorithm, decides what an activation does.

A *step* activates a set of robots at once (one robot for ASYNC; a round's Looks, Computes or Moves for
FSYNC/SSYNC). Moves in one step are simultaneous: two robots ending on one point, swapping across an edge,
or moving onto a robot that stays are collisions. A collision stops the run and is not applied.

Every step is recorded in :class:`~apf_viz.core.history.History`; :meth:`Engine.seek` restores any
earlier step from a checkpoint and re-applies the recorded choices, which reproduces the run exactly
because algorithms are deterministic.
"""

from __future__ import annotations

from collections.abc import Sequence
from itertools import chain
from typing import Literal

import numpy as np

from apf_viz.core.algorithm import Algorithm, Decision, Pattern
from apf_viz.core.engine_state import NEXT_EVENT, EngineState, Outcome, Phase
from apf_viz.core.fast_forward import (
    WalkMismatch,
    check_walks_requested,
    hidden_only_on_line,
    shifted,
    steps_in_same_sight,
    walk_mismatch,
)
from apf_viz.core.frames import move_to_global
from apf_viz.core.grid import COORD_LIMIT, Direction, Point, coordinate_problem
from apf_viz.core.history import Event, History, StepRecord, Walk
from apf_viz.core.pattern_match import matches_pattern
from apf_viz.core.view import Snapshot
from apf_viz.core.visibility import Views
from apf_viz.core.watches import Watches

LightSemantics = Literal["compute", "lc-atomic"]

# The memo holds views: bounded by the robots they list, not by their number, because the cyclic
# collector walks every one of them on each full pass (a big memo of 100-robot views cost more than it saved).
_DECISION_CACHE_ROBOTS = 400_000
# A view of many robots almost never recurs (any move it sees changes it), so hashing it into the memo
# costs more than the memo saves; a robot's repeated asks about one view are caught by identity instead.
_MEMO_MAX_ROBOTS = 24


_MAX_WALK_WAIT = 63  # cycles between two tries of a walk that did not go (see Engine.walk)
# Cycles of a crowd's walker looked ahead for watches at once (Engine._forced_cycles): its decision
# usually changes sooner, and a look further ahead costs no more.
_FORCED_HORIZON = 256
# Plain ints on the hot path: attribute access on an Enum class costs more than the rest of a step.
_IDLE, _LOOKED, _COMPUTED = int(Phase.IDLE), int(Phase.LOOKED), int(Phase.COMPUTED)
# Events are built with tuple.__new__: a NamedTuple's own __new__ (keywords, defaults) is a Python
# function and costs more than the rest of a no-op Move.
_new = tuple.__new__


class EngineError(ValueError):
    """A request the engine cannot carry out (bad robot index, mixed phases in one step, run over)."""


class Engine:
    """One run of an algorithm from a start configuration towards a pattern.

    Args:
        robots: start positions, global frame, distinct.
        pattern: target points (any translation; the algorithm embeds it).
        algorithm: the pure decision function every robot runs.
        y_up: per robot, whether its local +y is the global +y (the adversary's flips); all True if None.
        light_semantics: ``"compute"`` (a new light is visible from the end of Compute) or
            ``"lc-atomic"`` (Look and Compute are one atomic event).
        max_events: the run ends with outcome ``limit`` before its events could pass this many (None: no
            limit); under lc-atomic, where a Look step is two events, it may end one event short.
        max_moves: the same for moves (None: no limit).
        checkpoint_every: steps between state checkpoints used by :meth:`seek`.
        skip_noops: schedulers choose only among robots whose next event can change something
            (:meth:`eligible`); False keeps every no-op cycle (``--all-activations``).
        use_watches: when skipping, trust the :class:`~apf_viz.core.algorithm.Watch` of a no-op decision
            to tell when the robot must be asked again (False: after any change of its view; the same
            run, slower; for tests).
        fast_forward: when skipping, let :meth:`walk` apply a lone robot's repeating cycles as one
            macro-step (:mod:`apf_viz.core.fast_forward`); the same run, event for event.
        check_walks: re-decide every step a walk or forced cycles skip, on views built from scratch,
            and raise :class:`~apf_viz.core.fast_forward.WalkMismatch` on a difference (None: as
            ``APF_VIZ_CHECK_WALKS`` says; slow, for tests and ``--check-walks``).
    """

    def __init__(
        self,
        robots: Sequence[Point],
        pattern: Sequence[Point],
        algorithm: Algorithm,
        *,
        y_up: Sequence[bool] | None = None,
        light_semantics: LightSemantics = "compute",
        max_events: int | None = None,
        max_moves: int | None = None,
        checkpoint_every: int = 64,
        skip_noops: bool = True,
        use_watches: bool = True,
        fast_forward: bool = False,
        check_walks: bool | None = None,
    ) -> None:
        k = len(robots)
        if k == 0:
            raise EngineError("a run needs at least one robot")
        if len({tuple(p) for p in robots}) != k:
            raise EngineError("two robots start on the same point")
        problem = coordinate_problem(robots, "robot") or coordinate_problem(pattern, "pattern point")
        if problem:
            raise EngineError(problem)
        self.k = k
        self.start: tuple[Point, ...] = tuple((int(x), int(y)) for x, y in robots)
        self.pattern: Pattern = tuple((int(x), int(y)) for x, y in pattern)
        self.algorithm = algorithm
        self.y_up: tuple[bool, ...] = tuple(bool(b) for b in y_up) if y_up is not None else (True,) * k
        if len(self.y_up) != k:
            raise EngineError(f"y_up has {len(self.y_up)} entries for {k} robots")
        self.light_semantics: LightSemantics = light_semantics
        self.max_events = max_events
        # A robot's step makes one event, or two under lc-atomic (its Look and Compute): the run ends where
        # the next step could pass max_events, so it never holds more (one short of it, at worst).
        self._most_events_a_step = 2 if light_semantics == "lc-atomic" else 1
        self.max_moves = max_moves
        self.checkpoint_every = checkpoint_every
        self.skip_noops = skip_noops
        self.use_watches = use_watches
        self.fast_forward = fast_forward and skip_noops
        self.check_walks = check_walks_requested() if check_walks is None else check_walks
        self.walks = 0  # macro-steps applied by walk(), for benchmarks and tests
        self.broken_strides = 0  # strides whose last cycle decided otherwise (not walked), for tests
        self.forced_walks = 0  # runs of forced cycles applied by walk() (each cycle its own steps)
        # Per robot, cycles to let pass before trying a walk again, and the last such wait: in a crowd its
        # sight changes every few steps, and trying at every cycle would cost more than the walks save.
        self._walk_wait = [0] * k
        self._walk_backoff = [0] * k
        self._decisions: dict[Snapshot, Decision] = {}
        self._memo_robots = 0  # robots listed by the views in self._decisions
        self.decide_calls = 0  # algorithm invocations (cache misses), for benchmarks and tests
        self.state = self._initial_state()
        self.history = History(self.state.copy())
        self._views = self._new_views()
        self._watches = self._new_watches()
        # Each robot's last snapshot and what it was made of, reused while its view is unchanged.
        self._snaps: list[tuple[object, Snapshot] | None] = [None] * k
        self._probe: list[tuple[int, bool]] = [(-1, False)] * k  # (version, decision is a no-op)
        self._probe_hint = 0
        self._busy: tuple[int, int, int] = (-1, -1, -1)  # (robot, version, its last act) found active
        self._held: list[tuple[Snapshot, Decision] | None] = [None] * k  # each robot's last decision
        self._all = np.ones(k, dtype=bool)
        self._eligible = np.ones(k, dtype=bool)  # valid but for the robots in _dirty and _views.changed
        self._dirty: set[int] = set(range(k))
        # Bumped whenever a robot becomes eligible (and on seek): until then the eligible robots only
        # leave, so a fairness deadline computed over them stays valid (schedulers.base.most_starved).
        self.eligible_gained = 0
        if skip_noops and self.state.outcome is None and not self.eligible().any():
            self._update_outcome()  # a start on which no robot can ever act: stuck (or formed) at once

    # ------------------------------------------------------------------ read-only views
    @property
    def positions(self) -> np.ndarray:
        """Current positions, shape (k, 2), global frame. Do not mutate."""
        return self.state.positions

    @property
    def outcome(self) -> Outcome | None:
        return self.state.outcome

    @property
    def finished(self) -> bool:
        return self.state.outcome is not None

    @property
    def step_index(self) -> int:
        """Number of steps applied so far (the position on the timeline)."""
        return self.state.steps

    def next_event(self, robot: int) -> str:
        """``"look"``, ``"compute"`` or ``"move"``: what activating this robot does next."""
        return NEXT_EVENT[self.state.phase[robot]]

    def visible(self, robot: int) -> np.ndarray:
        """Indices of the robots this robot sees now."""
        return np.array(self._views.view(robot)[1], dtype=np.intp)

    def look(self, robot: int) -> Snapshot:
        """The snapshot this robot would take now (no event is recorded)."""
        return self._snapshot(robot)

    def decide(self, view: Snapshot) -> Decision:
        """The algorithm's decision on a view, memoised: the algorithm is pure, so a view seen before
        (by any robot, at any time) costs a dictionary look-up, not a recompute (views of up to
        ``_MEMO_MAX_ROBOTS`` robots; larger ones hardly ever recur)."""
        memo = len(view) <= _MEMO_MAX_ROBOTS
        if memo:
            hit = self._decisions.get(view)
            if hit is not None:
                return hit
        self.decide_calls += 1
        decision = self.algorithm.decide(view, self.pattern)
        if decision.light not in self.algorithm.lights:
            raise EngineError(f"algorithm {self.algorithm.name!r} set unknown light {decision.light!r}")
        if not memo:
            return decision
        self._memo_robots += len(view) + 1
        if self._memo_robots > _DECISION_CACHE_ROBOTS:
            self._decisions.clear()
            self._memo_robots = len(view) + 1
        self._decisions[view] = decision
        return decision

    def _decide(self, r: int, view: Snapshot) -> Decision:
        """:meth:`decide` for robot r: its Compute and the quiescence probes ask about the view it holds
        again and again, so the last one is matched by identity before the memo hashes a whole view."""
        held = self._held[r]
        if held is not None and held[0] is view:
            return held[1]
        decision = self.decide(view)
        self._held[r] = (view, decision)
        return decision

    def eligible(self) -> np.ndarray:
        """Which robots' next event can change anything, shape (k,) bool (do not mutate): a robot that
        has Looked or Computed, or an idle robot whose current view (with its own light) the algorithm
        answers with anything but "same light, stay". An idle robot outside it would run a whole cycle
        that changes nothing, and so would every later activation until its view changes; leaving it out
        is a legal ASYNC delay (docs/ALGORITHM.md, "Skipping what cannot change anything"). Only robots
        that acted or whose view changed since the last call are decided anew. All robots when
        ``skip_noops`` is off."""
        if not self.skip_noops:
            return self._all
        dirty = self._stale()
        if dirty:
            gained = False
            for r in dirty:
                gained = self._settle(r) or gained
            self._dirty = set()
            if gained:
                self.eligible_gained += 1
        return self._eligible

    def _stale(self) -> set[int]:
        """The robots to decide anew before their eligibility is current (acted, or their view changed)."""
        views = self._views
        if views.changed:
            self._dirty |= views.changed
            views.changed = set()
        return self._dirty

    def _settle(self, r: int) -> bool:
        """Make robot r's eligibility current (its watch, if its decision is one, registered); True if
        it became eligible. The caller removes it from the stale set."""
        st = self.state
        eligible = self._eligible
        self._watches.clear(r)
        was = bool(eligible[r])
        if st.phase[r] != _IDLE:
            eligible[r] = True
            return not was
        decision = self._decide(r, self.look(r))
        noop = decision.is_noop(st.lights[r])
        eligible[r] = not noop
        watch = decision.watch if noop and self.use_watches else None
        if watch is not None and self._watches.register(r, watch):
            self._views.release(r)  # no need to keep its view: the watch says when to look again
        return not (noop or was)

    def _new_views(self) -> Views:
        return Views(self.state.positions, self.state.lights, self.y_up, self.algorithm.lights)

    def _new_watches(self) -> Watches:
        return Watches(
            self.state.positions, self.state.lights, self.algorithm.lights, self.y_up, self._views.occupied
        )

    # ------------------------------------------------------------------ stepping
    def step(self, robots: Sequence[int], *, round: int | None = None) -> list[Event]:
        """Activate these robots simultaneously; each runs its next phase. Returns the events."""
        robots = tuple(map(int, robots))
        if len(robots) != 1 or not 0 <= robots[0] < self.k:  # the ASYNC case needs no more checks
            if not robots:
                raise EngineError("a step activates at least one robot")
            if len(set(robots)) != len(robots) or not all(0 <= r < self.k for r in robots):
                raise EngineError(f"bad robot selection {robots} for {self.k} robots")
            if len({int(self.state.phase[r]) for r in robots}) != 1:
                raise EngineError("robots activated together must be in the same phase")
        return self.apply(StepRecord(robots=robots, round=round))

    def apply(self, record: StepRecord) -> list[Event]:
        """Apply a scheduler's choice as it is (the checks of :meth:`step` are the caller's)."""
        st = self.state
        if st.outcome is not None:
            raise EngineError(f"the run is over ({st.outcome})")
        position = st.steps
        events = self._apply(record)
        self.history.record(position, record, events)
        self._checkpoint_after(position)
        return events

    def _apply(self, record: StepRecord) -> list[Event]:
        st = self.state
        robots, round = record
        if self.skip_noops:
            st.skipped += self.k - int(np.count_nonzero(self.eligible()))
        phase = st.phase[robots[0]]
        version = st.version
        if len(robots) == 1:  # ASYNC: one robot, one phase (two under lc-atomic)
            r = robots[0]
            if phase == _IDLE:
                events = [self._look(r, round)]
                if self.light_semantics == "lc-atomic":
                    events.append(self._compute(r, round))
            elif phase == _LOOKED:
                events = [self._compute(r, round)]
            else:
                events = self._move_one(r, round)
            st.last_act[r] = st.steps + 1
        else:
            if phase == _IDLE:
                events = [self._look(r, round) for r in robots]
                if self.light_semantics == "lc-atomic":
                    events += [self._compute(r, round) for r in robots]
            elif phase == _LOOKED:
                events = [self._compute(r, round) for r in robots]
            else:
                events = self._move(robots, round)
            st.last_act[list(robots)] = st.steps + 1
        self._dirty.update(robots)
        st.steps += 1
        st.events += len(events)
        if round is not None:
            st.round = max(st.round, round)
        # Only a Move or a light change can make the robots quiescent: a Look makes a robot hold the view
        # it already had, and a Compute that keeps the light holds the decision on that view as pending.
        self._update_outcome(phase == _COMPUTED or st.version != version)
        return events

    def walk(self, max_steps: int | None = None) -> int:
        """Apply the cycles of a lone robot at once: when it is the only robot whose next event can
        change anything (so a scheduler that serves the eligible robots has no choice), every other robot
        is watched, and its decision is a move that keeps its light. Where the decision promises a
        ``stride`` and the robot's sight stays the same, the cycles are one macro-step; else (a crowd)
        they are forced cycles, each Looked and decided anew (:meth:`_forced_cycles`). Either stops
        short of anything the other robots' watches, the budgets or ``max_steps`` would change
        (:mod:`apf_viz.core.fast_forward`). Returns the steps applied (0: none; the caller steps as
        usual)."""
        st = self.state
        if not self.fast_forward or st.outcome is not None or self.history.length != st.steps:
            return 0
        eligible = self.eligible()
        if np.count_nonzero(eligible) != 1 or self._watches.count != self.k - 1:
            return 0
        r = int(eligible.nonzero()[0][0])
        if st.phase[r] != _IDLE:
            return 0
        if self._walk_wait[r]:
            self._walk_wait[r] -= 1
            return 0
        snap, ids = self._observe(r)
        decision = self._decide(r, snap)
        if decision.move is None or decision.light != st.lights[r]:
            return 0
        per = 2 if self.light_semantics == "lc-atomic" else 3
        gmove = move_to_global(decision.move, self.y_up[r])
        delta = gmove.delta
        here = self._views.points[r]
        # A walk never carries a robot past the coordinates where the sight test's arithmetic is exact
        # (grid.COORD_LIMIT); beyond them the run goes on step by step.
        n = COORD_LIMIT - (here[0] * delta[0] + here[1] * delta[1])
        if self.max_events is not None:
            n = min(n, (self.max_events - st.events - 1) // 3)
        if self.max_moves is not None:
            n = min(n, self.max_moves - st.moves - 1)
        if max_steps is not None:
            n = min(n, max_steps // per)
        if n < 2:
            return 0  # a budget or the caller's limit: no reason to wait before the next try
        same = 0  # cycles that repeat this very decision on the same robots in sight
        if decision.stride >= 2 and hidden_only_on_line(st.positions, r, delta, snap.columns):
            same = steps_in_same_sight(snap.columns, decision.move, min(n, decision.stride))
            # The stride is the algorithm's promise; its last cycle is decided for real (one decision
            # on the view the walker will hold there), and a promise that fails there is not walked:
            # the cycles are then forced ones, each decided for real.
            if same >= 2 and self.decide(shifted(snap, decision.move, same - 1)) != decision:
                self.broken_strides += 1
                if self.check_walks:
                    raise WalkMismatch(
                        f"fast-forward: robot {r}'s stride of {decision.stride} on {decision.rule_id!r} is "
                        f"broken: its cycle {same} decides otherwise"
                    )
                same = 0
        # Else, in a crowd, cycles the scheduler cannot interleave, each Looked and decided anew.
        reach = same if same >= 2 else (min(n, _FORCED_HORIZON) if per == 3 else 0)
        if reach >= 2:
            reach = self._watches.quiet_steps(r, here, delta, reach)
        if reach < 2:
            self._walk_wait[r] = self._walk_backoff[r] = min(2 * self._walk_backoff[r] + 1, _MAX_WALK_WAIT)
            return 0
        self._walk_backoff[r] = 0
        if same >= 2:
            self._walk(r, here, gmove, snap, ids, decision, reach, per)
            return reach * per
        return self._forced_cycles(r, here, gmove, reach)

    def _forced_cycles(self, r: int, here: Point, gmove: Direction, n: int) -> int:
        """Apply up to n whole cycles of robot r, each Look, Compute and Move recorded as its own step
        exactly as the scheduler's forced choices would be, while its decision keeps its light and its
        move (``gmove``, global): :meth:`walk` checked that those n moves concern no watcher and leave
        every budget, so r stays the only eligible robot and no outcome can fall inside. Other robots'
        watches are told of the whole way once at the end. Returns the steps applied (0: none)."""
        st = self.state
        start = st.steps
        dx, dy = gmove.delta
        occupied = self._views.occupied
        light = st.lights[r]
        record = _new(StepRecord, ((r,), None))
        at = here
        cycles = 0
        while cycles < n:
            if cycles:
                decision = self._decide(r, self._observe(r)[0])
                if decision.light != light or move_to_global(decision.move, self.y_up[r]) != gmove:
                    break
            to = (at[0] + dx, at[1] + dy)
            if to in occupied:
                break  # a collision: stepped as usual
            self._forced_step(record, self._look(r, None))
            self._forced_step(record, self._compute(r, None))
            self._forced_step(record, self._move_quietly(r, at, to, None))
            at = to
            cycles += 1
        if not cycles:
            return 0
        if self.check_walks:
            self._check_walk(r, here, gmove, cycles, None)
        self.forced_walks += 1
        self._dirty.update(self._watches.moved((here,), (at,), (r,), occupied))
        self._dirty.add(r)
        self._update_outcome()
        self._checkpoint_after(start)
        return 3 * cycles

    def _check_walk(self, r: int, here: Point, gmove: Direction, n: int, decision: Decision | None) -> None:
        """``check_walks``: the n cycles of robot r from ``here`` are those the step-by-step run makes
        (:func:`~apf_viz.core.fast_forward.walk_mismatch`), or the run stops with the difference."""
        positions = self.state.positions.copy()
        positions[r] = here
        problem = walk_mismatch(
            positions, self.state.lights, self.y_up, r, gmove.delta, n, decision, self._decide_afresh
        )
        if problem:
            raise WalkMismatch(f"fast-forward is not the step-by-step run: {problem}")

    def _decide_afresh(self, view: Snapshot) -> Decision:
        """The algorithm's decision, asked directly (no memo): the walk check's independent witness."""
        return self.algorithm.decide(view, self.pattern)

    def _forced_step(self, record: StepRecord, event: Event) -> None:
        """The bookkeeping :meth:`apply` does around a step, for one of :meth:`_forced_cycles`' events
        (the robot already acted): the others skipped, its last act, the counts, the history."""
        st = self.state
        st.skipped += self.k - 1
        st.last_act[event.robot] = st.steps + 1
        st.steps += 1
        st.events += 1
        self.history.record(st.steps - 1, record, [event])

    def _checkpoint_after(self, position: int) -> None:
        """A checkpoint of the state after the steps from ``position`` when they crossed a multiple of
        ``checkpoint_every``; taken once the outcome is settled, so that a seek there restores it."""
        st = self.state
        if position // self.checkpoint_every != st.steps // self.checkpoint_every:
            self.history.checkpoint(st.steps, st.copy())

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
        assert decision.move is not None  # a walk moves
        st = self.state
        if self.check_walks:
            self._check_walk(r, here, gmove, n, decision)
        dx, dy = gmove.delta
        to = (here[0] + n * dx, here[1] + n * dy)
        position = st.steps
        st.positions[r] = to
        self._views.moved((r,), (here,))
        self._dirty.update(self._watches.moved((here,), (to,), (r,), self._views.occupied))
        self._dirty.add(r)
        st.steps += n * per
        st.events += 3 * n
        st.moves += n
        st.cycles += n
        st.version += n
        st.skipped += (self.k - 1) * n * per
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
        self.history.record_walk(position, Walk.of(r, n * per, per, look, compute, here, (dx, dy)))
        self._update_outcome()
        self._checkpoint_after(position)

    def _look(self, r: int, round: int | None) -> Event:
        st = self.state
        snap, ids = self._observe(r)
        self._views.prime_seen_bits(r, ids)
        st.snapshot[r] = snap
        st.seen[r] = ids
        st.look_step[r] = st.steps + 1
        st.look_version[r] = st.version
        st.phase[r] = _LOOKED
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
        st.phase[r] = _COMPUTED
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
        st.phase[r] = _IDLE
        st.pending[r] = None
        st.snapshot[r] = None
        st.seen[r] = None
        st.cycles += 1
        st.last_cycle_end[r] = st.steps + 1

    # ------------------------------------------------------------------ outcomes
    def settle_outcome(self) -> None:
        """Decide now whether the run is over (formed or stuck), as after a Move: for an engine that
        keeps every activation, which looks only after a step, so that a trace that ends where no robot
        can act (a deadlock at the start: no step at all) replays as stuck, not as running."""
        self._update_outcome()

    def _update_outcome(self, changed: bool = True) -> None:
        st = self.state
        if st.outcome is not None:
            return
        if changed and self._quiescent():
            st.outcome = "formed" if matches_pattern(self.current_points(), self.pattern) else "stuck"
        elif (self.max_events is not None and st.events + self._most_events_a_step > self.max_events) or (
            self.max_moves is not None and st.moves >= self.max_moves
        ):
            st.outcome = "limit"

    def _quiescent(self) -> bool:
        """True when no robot can change anything, whatever the scheduler does from here: every robot's
        held snapshot (if it has Looked) and its view of the current configuration both lead to "same
        light, stay", and no move is pending. (Under stale-first robots are rarely all idle at once, so
        "all idle" is not required; an idle robot is the special case with nothing held.)

        Probes of the current view are cached per configuration version, and the robot found active last
        time is probed first, so a busy run pays at most one Look per configuration change. When skipping,
        every idle robot's answer is its eligibility: :meth:`_active_before_deciding` decides."""
        if self.skip_noops:
            return not self._active_before_deciding()
        hint = self._probe_hint
        if self._busy == (hint, self.state.version, self.state.last_act[hint]):
            return False  # found active, and neither it nor the configuration has changed since
        if not self._robot_quiescent(hint):  # the usual case: the last active robot still is
            self._busy = (hint, self.state.version, self.state.last_act[hint])
            return False
        for r in chain(range(self._probe_hint + 1, self.k), range(self._probe_hint)):
            if not self._robot_quiescent(r):
                self._probe_hint = r
                return False
        return True

    def _active_before_deciding(self) -> bool:
        """Whether some robot can act, found while deciding as few of the stale robots (:meth:`_stale`)
        as it can: one whose eligibility is current and which is idle or has something left to do, one
        of them in mid-cycle (eligible whatever it sees) with something left to do, or the first of them
        decided eligible. After a light a crowd sees, the rest are decided when the scheduler next asks
        (:meth:`eligible`), after the frame that shows the light. Deciding them in two parts changes no
        answer: each robot's depends only on the configuration, the same until the next step. False
        only once every eligible robot has been looked at: the run is quiescent (the mid-cycle robots
        left stale are eligible, and were found to have nothing to do)."""
        stale = self._stale()
        phase = self.state.phase
        for r in self._eligible.nonzero()[0].tolist():
            if r not in stale and (phase[r] == _IDLE or not self._robot_quiescent(r)):
                return True
        if any(phase[r] != _IDLE and not self._robot_quiescent(r) for r in stale):
            return True
        for r in [r for r in stale if phase[r] == _IDLE]:
            stale.discard(r)
            if self._settle(r):
                self.eligible_gained += 1  # counted per part: the schedulers ask only whether it changed
            if self._eligible[r]:
                return True
        return False

    @property
    def pending_decisions(self) -> int:
        """How many robots (at most) must be decided anew before the next scheduler's choice: the cost
        the next step carries before its own event."""
        return len(self._dirty) + len(self._views.changed) if self.skip_noops else 0

    def _robot_quiescent(self, r: int) -> bool:
        st = self.state
        phase = st.phase[r]
        pending, snap = st.pending[r], st.snapshot[r]
        if phase == _COMPUTED and pending is not None and pending.move is not None:
            return False
        if phase == _LOOKED and snap is not None and not self._decide(r, snap).is_noop(st.lights[r]):
            return False
        version, noop = self._probe[r]
        if version != st.version:
            noop = self._decide(r, self.look(r)).is_noop(st.lights[r])
            self._probe[r] = (st.version, noop)
        return noop

    def current_points(self) -> list[Point]:
        return list(map(tuple, self.state.positions.tolist()))

    # ------------------------------------------------------------------ time travel
    def seek(self, step: int) -> None:
        """Go to the state after ``step`` steps of the recorded history (0 = the start).

        The steps after it stay recorded until a different step is taken from here (a branch)."""
        if not 0 <= step <= self.history.length:
            raise EngineError(f"step {step} is outside the recorded history 0..{self.history.length}")
        base, state = self.history.checkpoint_before(step)
        self.state = state.copy()
        self._views = self._new_views()
        self._watches = self._new_watches()
        self._probe = [(-1, False)] * self.k
        self._busy = (-1, -1, -1)
        self._snaps = [None] * self.k
        self._dirty = set(range(self.k))
        self.eligible_gained += 1
        for i in range(base, step):
            self._apply(self.history.steps.record(i))

    def back(self, n: int = 1) -> None:
        """Undo the last ``n`` steps."""
        self.seek(max(0, self.state.steps - n))

    def redo(self) -> list[Event] | None:
        """Re-apply the next recorded step after a :meth:`seek`, if there is one."""
        if self.state.steps >= self.history.length:
            return None
        record = self.history.steps.record(self.state.steps)
        return self.step(record.robots, round=record.round)

    # ------------------------------------------------------------------ internals
    def _initial_state(self) -> EngineState:
        k = self.k
        first = self.algorithm.lights[0]
        return EngineState(
            positions=np.array(self.start, dtype=np.int64).reshape(k, 2),
            lights=[first] * k,
            phase=np.zeros(k, dtype=np.int8),
            snapshot=[None] * k,
            seen=[None] * k,
            look_step=np.zeros(k, dtype=np.int64),
            look_version=[-1] * k,
            pending=[None] * k,
            decided=[None] * k,
            decided_seen=[None] * k,
            decided_look=np.zeros(k, dtype=np.int64),
            last_act=np.zeros(k, dtype=np.int64),
            last_cycle_end=np.zeros(k, dtype=np.int64),
            lights_used={first},
            # The pattern is already formed: nothing any robot does can form it sooner (docs/ALGORITHM.md,
            # "A start that is the pattern").
            outcome="formed" if matches_pattern(self.start, self.pattern) else None,
        )
