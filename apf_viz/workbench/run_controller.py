"""The run everyone sees: the engine, the adversary (scheduler and seed) and the play state.

Every change goes through a method, under one lock: viser runs callbacks on its own threads, and the
render thread plays. A change of algorithm, light semantics, start or pattern rebuilds the run from a
new :class:`~apf_viz.workbench.run_config.RunConfig`; nothing is reset field by field.
"""

from __future__ import annotations

import threading
from collections.abc import Mapping

from apf_viz.algorithms import Factory, get_algorithm
from apf_viz.core.engine import Engine
from apf_viz.core.formats import InputError
from apf_viz.core.history import StepRecord
from apf_viz.core.portrayal import Configuration, stage_of
from apf_viz.core.schedulers import BY_HAND, make_scheduler, step_rng
from apf_viz.workbench.move_series import MoveSeries
from apf_viz.workbench.run_config import RunConfig
from apf_viz.workbench.stage_log import StageLog

# Steps per second: the Speed slider's top. Play never spends more than a share of each frame stepping
# (ui/app.py STEP_SHARE), so a speed the engine cannot reach plays as fast as it can at full frame rate.
MAX_SPEED = 5000.0


class RunController:
    """One run, its adversary and whether it plays."""

    def __init__(self, config: RunConfig, plugins: Mapping[str, Factory] | None = None) -> None:
        self.lock = threading.RLock()
        # The only algorithms a name from a trace may choose: built-ins and what the command line loaded.
        self.plugins: Mapping[str, Factory] = dict(plugins or {})
        self._playing = False
        self._speed = 10.0
        self._rebuild(config)

    # ------------------------------------------------------------------ reading
    @property
    def playing(self) -> bool:
        return self._playing

    @property
    def speed(self) -> float:
        """Steps per second while playing."""
        return self._speed

    @property
    def series(self) -> MoveSeries:
        return self._series

    @property
    def stages(self) -> StageLog:
        """Where each of the algorithm's stages began in this run (the timeline's marks)."""
        return self._stages

    # ------------------------------------------------------------------ building
    def _rebuild(
        self,
        config: RunConfig,
        engine: Engine | None = None,
        trace_events: int = 0,
        trace_options: Mapping[str, object] | None = None,
    ) -> None:
        make_scheduler(config.scheduler)  # validates the name
        self.engine = engine if engine is not None else config.engine(self.plugins)
        self.config = config
        self._series = MoveSeries(self.engine.start)
        algorithm, pattern, start = self.engine.algorithm, config.pattern, config.robots
        self._stages = StageLog(
            self.engine.start,
            [algorithm.lights[0]] * self.engine.k,
            lambda pts, lights: stage_of(algorithm, Configuration(pts, lights, pattern, start)),
        )
        self._playing = False
        # A replayed trace is followed step by step until the person branches (Branch here).
        self.following = engine is not None and engine.history.length > 0
        self.following_what = "the trace"
        # Steps a branch dropped (where, what), so that the person can go back to them.
        self.set_aside: tuple[int, list[StepRecord]] | None = None
        self.trace_events = trace_events if self.following else 0
        # What the trace's header says about it (a verdict, a livelock's loop): kept for this run.
        self.trace_options: dict[str, object] = dict(trace_options or {}) if self.following else {}

    @property
    def trace_position(self) -> tuple[int, int] | None:
        """(events so far, events in the trace) while a trace is followed, else None."""
        return (self.engine.state.events, self.trace_events) if self.following else None

    def branch_here(self) -> None:
        """Leave the trace: from here the scheduler (or Manual) chooses; the recorded future is dropped
        by the first step that differs from it."""
        with self.lock:
            self.following = False

    def restart(self, config: RunConfig) -> None:
        """A new run from this configuration (a new start, pattern, algorithm or light semantics)."""
        with self.lock:
            self._rebuild(config)

    def adopt(
        self,
        config: RunConfig,
        engine: Engine,
        trace_events: int,
        trace_options: Mapping[str, object] | None = None,
        what: str = "the trace",
    ) -> None:
        """Take over an engine built elsewhere (a replayed trace of ``trace_events`` events, whose header
        has ``trace_options``, or a followed schedule: ``what``), at its start; Step then follows it."""
        with self.lock:
            engine.seek(0)
            engine.skip_noops = config.skip_noops  # it replayed with every activation; a branch skips
            if not trace_events:
                engine.settle_outcome()  # a trace of a start where nobody can act: stuck at once
            self._rebuild(config, engine, trace_events, trace_options)
            self.following_what = what

    def reset(self) -> None:
        """Back to the start of the same run."""
        self.restart(self.config)

    # ------------------------------------------------------------------ the adversary
    def set_scheduler(self, name: str) -> None:
        make_scheduler(name)  # validates the name before anything changes
        with self.lock:
            self.config = self.config.but(scheduler=name)

    def set_seed(self, seed: float) -> None:
        """A seed typed in the browser: a whole number in 0 .. 2^63 − 1, anything else is refused."""
        if not (isinstance(seed, int | float) and float(seed).is_integer() and 0 <= seed < 2**63):
            raise InputError(f"seed {seed!r}: a seed is a whole number from 0 to 2^63 − 1")
        with self.lock:
            self.config = self.config.but(seed=int(seed))

    def set_algorithm(self, name: str) -> None:
        """Restart the same start and pattern under another algorithm (built in, ``@…``, or a plug-in
        the command line loaded)."""
        get_algorithm(name, self.plugins)  # refuses an unknown name before anything changes
        self.restart(self.config.but(algorithm=name))

    def set_skip_noops(self, skip: bool) -> None:
        """Whether schedulers pass over robots whose next cycle changes nothing (the run restarts: its
        history would mix both)."""
        self.restart(self.config.but(skip_noops=bool(skip)))

    def set_light_semantics(self, semantics: str) -> None:
        if semantics not in ("compute", "lc-atomic"):
            raise InputError(f"light semantics {semantics!r}: choose compute or lc-atomic")
        self.restart(self.config.but(light_semantics=semantics))

    # ------------------------------------------------------------------ stepping
    def step(self) -> bool:
        """One step chosen by the scheduler. False if the run is over (or the scheduler is Manual)."""
        with self.lock:
            if self.following:  # the trace decides: its next recorded step, until its end
                return not self.engine.finished and self.engine.redo() is not None
            if self.engine.finished or self.config.scheduler in BY_HAND:
                return False
            record = make_scheduler(self.config.scheduler).choose(
                self.engine, step_rng(self.config.seed, self.engine.step_index)
            )
            self._branching_step(record.robots, record.round)
            return True

    def step_robot(self, robot: int) -> str:
        """Manual: run this robot's next phase. Returns the phase run."""
        with self.lock:
            phase = self.engine.next_event(robot)
            self._branching_step([robot], None)
            self.following = False  # a person's choice leaves the trace
            return phase

    def _branching_step(self, robots, round: int | None) -> None:
        """A step that may differ from the recorded future: then the future is set aside, not lost."""
        history = self.engine.history
        generation = history.generation
        self.engine.step(robots, round=round)
        if history.generation != generation and history.dropped is not None:
            self.set_aside = history.dropped

    def return_to_set_aside(self) -> None:
        """Go back to the steps a branch dropped: replay them from where they were dropped, then follow
        them (Step, Play) from there. The branch left is set aside in turn, so this toggles."""
        with self.lock:
            if self.set_aside is None:
                raise InputError("no branch was set aside")
            at, records = self.set_aside
            e = self.engine
            self._playing = False
            e.seek(at)
            generation = e.history.generation
            for record in records:
                if e.finished:
                    break
                e.step(record.robots, round=record.round)
            left = e.history.dropped if e.history.generation != generation else None
            self.trace_events = e.state.events
            e.seek(at)
            self.set_aside = left
            self.following, self.following_what = True, "the set-aside branch"

    def back(self) -> None:
        with self.lock:
            self._playing = False
            self.engine.back(1)

    def seek(self, step: float) -> None:
        """Go to a step of the history (clamped); NaN or a non-number is refused."""
        if not isinstance(step, int | float) or step != step:
            raise InputError(f"timeline position {step!r} is not a number")
        with self.lock:
            self._playing = False
            self.engine.seek(int(min(max(step, 0), self.engine.history.length)))

    # ------------------------------------------------------------------ playing
    def play(self) -> None:
        with self.lock:
            self._playing = not self.engine.finished

    def pause(self) -> None:
        with self.lock:
            self._playing = False

    def toggle_play(self, beside: bool = False) -> None:
        """Play or pause; ``beside``: the run has ended but Compare's run beside it can go on alone, so
        Play plays that one (the session steps it)."""
        with self.lock:
            self._playing = not self._playing and (beside or not self.engine.finished)

    def set_speed(self, speed: float) -> None:
        """Steps per second while playing, clamped to 1 .. MAX_SPEED (a browser may send anything)."""
        if not isinstance(speed, int | float) or speed != speed:  # NaN
            raise InputError(f"speed {speed!r} is not a number")
        with self.lock:
            self._speed = float(min(max(speed, 1.0), MAX_SPEED))

    def play_steps(self, allowance: int = 1) -> int:
        """Up to ``allowance`` steps of Play, at least one; stops playing when nothing could run. Returns
        the steps taken. Where the scheduler has no choice (one robot can act) and the allowance holds
        whole cycles, they are one walk (core/fast_forward.py): the same steps, recorded one by one."""
        with self.lock:
            if not self._playing:
                return 0
            scheduler = self.config.scheduler
            if allowance >= 3 and not self.following and make_scheduler(scheduler).forced_when_alone:
                taken = self.engine.walk(allowance)  # Manual is never forced: the person chooses
                if taken:
                    return taken
            if not self.step():
                self._playing = False
                return 0
            return 1
