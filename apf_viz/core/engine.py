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

import numpy as np

from apf_viz.core.engine_core import EngineCore, EngineError, LightSemantics
from apf_viz.core.engine_state import COMPUTED, IDLE, LOOKED, NEXT_EVENT
from apf_viz.core.events import Events
from apf_viz.core.history import Event, StepRecord
from apf_viz.core.walking import Walker

__all__ = ["NEXT_EVENT", "Engine", "EngineError", "LightSemantics"]


class Engine(EngineCore):
    """One run of an algorithm from a start configuration towards a pattern.

    Args:
        robots: start positions, global frame, distinct.
        pattern: target points (any translation; the algorithm embeds it).
        algorithm: the pure decision function every robot runs.
        y_up: per robot, whether its local +y is the global +y (the adversary's flips); all True if None.
        light_semantics: ``"compute"`` (a new light is visible from the end of Compute) or
            ``"lc-atomic"`` (Look and Compute are one atomic event).
        max_events: the run ends with outcome ``limit`` before its events could pass this many (None: no
            limit), under every scheduler: a step that would pass it (a synchronous round of many robots,
            a Look and Compute as one under lc-atomic) is not taken; it may end a step short of it.
        max_moves: the same for moves (None: no limit).
        max_recorded: the run ends with outcome ``limit`` when its history holds this many entries (a
            step each, a fast-forwarded walk one): memory bounded at any distance (None: no limit).
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

    def _begin_parts(self) -> None:
        self.events = Events(self)  # Look, Compute, Move: what a step does to the state
        self.walker = Walker(self, self.events)  # fast-forward: a lone robot's cycles at once

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
        # A round of many robots, or a Look and its Compute as one under lc-atomic, may not pass the cap.
        both = self.light_semantics == "lc-atomic" and st.phase[record[0][0]] == IDLE
        if self.max_events is not None and st.events + len(record[0]) * (1 + both) > self.max_events:
            st.outcome = "limit"
            return []
        position = st.steps
        events = self._apply(record)
        self.history.record(position, record, events)
        self._checkpoint_after(position)
        return events

    def _apply(self, record: StepRecord) -> list[Event]:
        st = self.state
        robots, round = record
        if self.skip_noops and self.counts_passed_over:
            st.skipped += self.k - int(np.count_nonzero(self.eligible()))
        phase = st.phase[robots[0]]
        version = st.version
        act = self.events
        if len(robots) == 1:  # ASYNC: one robot, one phase (two under lc-atomic)
            r = robots[0]
            if phase == IDLE:
                events = [act.look(r, round)]
                if self.light_semantics == "lc-atomic":
                    events.append(act.compute(r, round))
            elif phase == LOOKED:
                events = [act.compute(r, round)]
            else:
                events = act.move_one(r, round)
            st.last_act[r] = st.steps + 1
        else:
            if phase == IDLE:
                events = [act.look(r, round) for r in robots]
                if self.light_semantics == "lc-atomic":
                    events += [act.compute(r, round) for r in robots]
            elif phase == LOOKED:
                events = [act.compute(r, round) for r in robots]
            else:
                events = act.move(robots, round)
            st.last_act[list(robots)] = st.steps + 1
        self._dirty.update(robots)
        st.steps += 1
        st.events += len(events)
        if round is not None:
            st.round = max(st.round, round)
        # Only a Move or a light change can make the robots quiescent: a Look makes a robot hold the view
        # it already had, and a Compute that keeps the light holds the decision on that view as pending.
        self._update_outcome(phase == COMPUTED or st.version != version)
        return events

    # ------------------------------------------------------------------ fast-forward
    def walk(self, max_steps: int | None = None) -> int:
        """Apply a lone robot's cycles at once where the scheduler has no choice (:meth:`Walker.walk`);
        the steps applied (0: none, step as usual)."""
        return self.walker.walk(max_steps)

    @property
    def walks(self) -> int:
        """Macro-steps applied by :meth:`walk` (benchmarks and tests)."""
        return self.walker.walks

    @property
    def forced_walks(self) -> int:
        """Runs of forced cycles applied by :meth:`walk` (each cycle its own steps)."""
        return self.walker.forced_walks

    @property
    def broken_strides(self) -> int:
        """Strides whose last cycle decided otherwise (not walked), for tests."""
        return self.walker.broken_strides

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
