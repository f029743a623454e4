"""The engine's state and what its parts share (:class:`EngineCore`): robots' phases, snapshots and
pending decisions, the patched views, the watches, the memo of decisions, which robots can act (skipping
the cycles that change nothing) and whether the run is over. core/engine.py steps it."""

from __future__ import annotations

from collections.abc import Sequence
from itertools import chain
from typing import Literal

import numpy as np

from apf_viz.core.algorithm import Algorithm, Decision, Pattern
from apf_viz.core.budget import MAX_RECORDED
from apf_viz.core.engine_state import COMPUTED, IDLE, LOOKED, NEXT_EVENT, EngineState, Outcome
from apf_viz.core.fast_forward import check_walks_requested
from apf_viz.core.grid import Point, coordinate_problem
from apf_viz.core.history import History
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


# Plain ints on the hot path: attribute access on an Enum class costs more than the rest of a step.
# Events are built with tuple.__new__: a NamedTuple's own __new__ (keywords, defaults) is a Python
# function and costs more than the rest of a no-op Move.
_new = tuple.__new__


class EngineError(ValueError):
    """A request the engine cannot carry out (bad robot index, mixed phases in one step, run over)."""


def _checked_start(
    robots: Sequence[Point], pattern: Sequence[Point], y_up: Sequence[bool] | None
) -> tuple[tuple[Point, ...], Pattern, tuple[bool, ...]]:
    """The start, the pattern and the flips as the engine keeps them, or an :class:`EngineError`: no
    robot, two on one point, a coordinate out of range, flips of another length."""
    k = len(robots)
    if k == 0:
        raise EngineError("a run needs at least one robot")
    if len({tuple(p) for p in robots}) != k:
        raise EngineError("two robots start on the same point")
    problem = coordinate_problem(robots, "robot") or coordinate_problem(pattern, "pattern point")
    if problem:
        raise EngineError(problem)
    flips = tuple(bool(b) for b in y_up) if y_up is not None else (True,) * k
    if len(flips) != k:
        raise EngineError(f"y_up has {len(flips)} entries for {k} robots")
    start = tuple((int(x), int(y)) for x, y in robots)
    return start, tuple((int(x), int(y)) for x, y in pattern), flips


class EngineCore:
    """The engine's state and what its parts share: each robot's phase, snapshot and pending decision,
    the patched views and the watches, the memo of decisions, which robots can act, and the outcome.
    :class:`Engine` adds the steps and time travel, and holds the parts that change the state: the
    events (:class:`~apf_viz.core.events.Events`) and fast-forward (:class:`~apf_viz.core.walking.Walker`).
    Args: as :class:`Engine`'s."""

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
        max_recorded: int | None = MAX_RECORDED,
        checkpoint_every: int = 64,
        skip_noops: bool = True,
        use_watches: bool = True,
        fast_forward: bool = False,
        check_walks: bool | None = None,
    ) -> None:
        self.start, self.pattern, self.y_up = _checked_start(robots, pattern, y_up)
        self.k = k = len(self.start)
        self.algorithm = algorithm
        self.light_semantics: LightSemantics = light_semantics
        self.max_events = max_events
        # A robot's step makes one event, or two under lc-atomic (its Look and Compute).
        self._most_events_a_step = 2 if light_semantics == "lc-atomic" else 1
        self.max_moves = max_moves
        self.max_recorded = max_recorded
        self.checkpoint_every = checkpoint_every
        self.skip_noops = skip_noops
        # Whether a step counts the robots its chooser passed over (a schedule file passes nobody over).
        self.counts_passed_over = True
        self.use_watches = use_watches
        self.fast_forward = fast_forward and skip_noops
        self.check_walks = check_walks_requested() if check_walks is None else check_walks
        self._decisions: dict[Snapshot, Decision] = {}
        self._memo_robots = 0  # robots listed by the views in self._decisions
        self.decide_calls = 0  # algorithm invocations (cache misses), for benchmarks and tests
        self.state = self._initial_state()
        self.history = History(self.state.copy())
        self._views = self._new_views()
        self._watches = self._new_watches()
        self._start_skipping(k)
        self._begin_parts()
        if skip_noops and self.state.outcome is None and not self.eligible().any():
            self._update_outcome()  # a start on which no robot can ever act: stuck (or formed) at once

    def _begin_parts(self) -> None:
        """Where :class:`Engine` makes the parts that act on this state (before the start's outcome)."""

    def _start_skipping(self, k: int) -> None:
        """What passing over the robots whose next cycle changes nothing keeps (:meth:`eligible`)."""
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

    # ------------------------------------------------------------------ read-only views
    @property
    def positions(self) -> np.ndarray:
        """Current positions, shape (k, 2), global frame. Do not mutate."""
        return self.state.positions

    @property
    def outcome(self) -> Outcome | None:
        """How the run ended (``formed``, ``stuck``, ``limit``, ``collision``), or None while it goes on."""
        return self.state.outcome

    @property
    def finished(self) -> bool:
        """Whether the run is over: it has an outcome."""
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
        if st.phase[r] != IDLE:
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

    def _checkpoint_after(self, position: int) -> None:
        """A checkpoint of the state after the steps from ``position`` when they crossed a multiple of
        ``checkpoint_every``; taken once the outcome is settled, so that a seek there restores it."""
        st = self.state
        if position // self.checkpoint_every != st.steps // self.checkpoint_every:
            self.history.checkpoint(st.steps, st.copy())

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
        elif (
            (self.max_events is not None and st.events + self._most_events_a_step > self.max_events)
            or (self.max_moves is not None and st.moves >= self.max_moves)
            or (self.max_recorded is not None and self.history.entries >= self.max_recorded - 1)
        ):
            # (a step is recorded after this check, a walk before: either way at most max_recorded)
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
            if r not in stale and (phase[r] == IDLE or not self._robot_quiescent(r)):
                return True
        if any(phase[r] != IDLE and not self._robot_quiescent(r) for r in stale):
            return True
        for r in [r for r in stale if phase[r] == IDLE]:
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
        if phase == COMPUTED and pending is not None and pending.move is not None:
            return False
        if phase == LOOKED and snap is not None and not self._decide(r, snap).is_noop(st.lights[r]):
            return False
        version, noop = self._probe[r]
        if version != st.version:
            noop = self._decide(r, self.look(r)).is_noop(st.lights[r])
            self._probe[r] = (st.version, noop)
        return noop

    def current_points(self) -> list[Point]:
        """The robots' positions now, global frame, as a list of points (robot i's at index i)."""
        return list(map(tuple, self.state.positions.tolist()))

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
