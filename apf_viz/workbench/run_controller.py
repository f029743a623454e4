"""The run everyone sees: the engine, the adversary (scheduler and seed) and the play state.

Every change goes through a method, under one lock: viser runs callbacks on its own threads, and the
render thread plays. A change of algorithm, light semantics, start or pattern rebuilds the run from a
new :class:`~apf_viz.workbench.run_config.RunConfig`; nothing is reset field by field.
"""

from __future__ import annotations

import threading
from collections.abc import Mapping, Sequence

from apf_viz.algorithms import Factory, get_algorithm
from apf_viz.core.engine import Engine
from apf_viz.core.formats import InputError
from apf_viz.core.portrayal import Configuration, stage_of
from apf_viz.core.schedulers import BY_HAND, make_scheduler, step_rng
from apf_viz.workbench.branches import Branches, ending
from apf_viz.workbench.move_series import MoveSeries
from apf_viz.workbench.run_config import RunConfig
from apf_viz.workbench.stage_log import StageLog

# Steps per second: the Speed slider's top. Play never spends more than a share of each frame stepping
# (ui/app.py STEP_SHARE), so a speed the engine cannot reach plays as fast as it can at full frame rate.
MAX_SPEED = 5000.0

# The rungs an arrow key climbs on the Speed slider: its range spans four decades, and a step of one
# (5000 presses from end to end) is no step at all. A drag or a typed value still lands anywhere.
SPEED_LADDER = (1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0, 2000.0, MAX_SPEED)


def slider_speed(shown: float, sent: float) -> float:
    """The speed meant by a Speed slider that showed ``shown`` and now sends ``sent``: one unit up or
    down is an arrow key (the slider's step), read as the next rung of SPEED_LADDER that way; anything
    else is the value itself."""
    if abs(sent - shown) != 1:
        return sent
    if sent > shown:
        return next((rung for rung in SPEED_LADDER if rung > shown), MAX_SPEED)
    return next((rung for rung in reversed(SPEED_LADDER) if rung < shown), SPEED_LADDER[0])


class RunController:
    """One run, its adversary and whether it plays."""

    def __init__(self, config: RunConfig, plugins: Mapping[str, Factory] | None = None) -> None:
        self.lock = threading.RLock()
        # The only algorithms a name from a trace may choose: built-ins and what the command line loaded.
        self.plugins: Mapping[str, Factory] = dict(plugins or {})
        self._playing = False
        self._stop_at: int | None = None  # Play stops at this step (a question's reveal plays to it)
        self._speed = 10.0
        self._rebuild(config)

    # ------------------------------------------------------------------ reading
    @property
    def playing(self) -> bool:
        """Whether Play is on."""
        return self._playing

    @property
    def speed(self) -> float:
        """Steps per second while playing."""
        return self._speed

    @property
    def series(self) -> MoveSeries:
        """The run's (events, moves) after each recorded step (the moves chart)."""
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
        # A followed schedule's notes, by the step whose line carried them (kept while those steps are).
        self.step_notes: dict[int, str] = {}
        # Every line of steps a branch dropped, so that the person can go back to any of them.
        self.branches = Branches()
        # How the recorded line ends, as last seen at its end: (history generation, length, words, outcome).
        self._line_end: tuple[int, int, str, str | None] = (-1, -1, "", None)
        if engine is not None:
            self._note_end()
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
            self.trace_options = {}  # its verdict and loop describe the trace, not the run it becomes

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
            self.engine = engine
            self._note_end_of(engine)  # it was replayed to its end: how a branch left from it ends
            line_end = self._line_end
            engine.seek(0)
            engine.skip_noops = config.skip_noops  # it replayed with every activation; a branch skips
            if not trace_events:
                engine.settle_outcome()  # a trace of a start where nobody can act: stuck at once
            self._rebuild(config, engine, trace_events, trace_options)
            self._line_end = line_end
            self.following_what = what

    def reset(self) -> None:
        """Back to the start of the same run."""
        self.restart(self.config)

    # ------------------------------------------------------------------ the adversary
    def set_scheduler(self, name: str) -> None:
        """The adversary for the steps to come (the run goes on from where it stands); an unknown name is
        refused before anything changes."""
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
        """Restart the run under ``compute`` (a new light visible from the end of Compute) or ``lc-atomic``
        (Look and Compute one atomic event); anything else is refused."""
        if semantics not in ("compute", "lc-atomic"):
            raise InputError(f"light semantics {semantics!r}: choose compute or lc-atomic")
        self.restart(self.config.but(light_semantics=semantics))

    # ------------------------------------------------------------------ stepping
    def step(self) -> bool:
        """One step chosen by the scheduler. False if the run is over (or the scheduler is Manual)."""
        with self.lock:
            if self.following:  # the trace decides: its next recorded step, until its end
                stepped = not self.engine.finished and self.engine.redo() is not None
                self._note_end()
                return stepped
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
            generation = self.engine.history.generation
            self._branching_step([robot], None)
            # A person's choice that leaves the trace leaves what its header said too; one that is the
            # trace's own next step (its future kept) follows it still.
            if self.following and self.engine.history.generation != generation:
                self.following, self.trace_options = False, {}
            return phase

    def _branching_step(self, robots: Sequence[int], round: int | None) -> None:
        """A step that may differ from the recorded future: then the future is kept as a branch."""
        history = self.engine.history
        generation = history.generation
        line_end = self._end_words(generation, history.length)
        self.engine.step(robots, round=round)
        if history.generation != generation and history.dropped is not None:
            at, records = history.dropped
            self.branches.keep(at, records, line_end)
            self.step_notes = {n: note for n, note in self.step_notes.items() if n <= at}
        self._note_end()

    def note_here(self) -> str:
        """The note a schedule's line wrote for the step just taken, if any."""
        return self.step_notes.get(self.engine.step_index, "")

    def _end_words(self, generation: int, length: int) -> str:
        """How the recorded line of that generation and length ends, if it was seen at its end."""
        seen_generation, seen_length, words, _ = self._line_end
        if (seen_generation, seen_length) == (generation, length):
            return words
        return f"recorded to step {length}, not played to its end"

    def _note_end(self) -> None:
        self._note_end_of(self.engine)

    def _note_end_of(self, engine: Engine) -> None:
        """Remember how the line ends when the engine stands at the end of its history."""
        if engine.step_index == engine.history.length:
            h = engine.history
            self._line_end = (h.generation, h.length, ending(engine), engine.state.outcome or "running")

    def line_verdict(self) -> dict[str, object]:
        """How the recorded line ends, if it was seen at its end: a trace header's verdict."""
        generation, length, words, outcome = self._line_end
        h = self.engine.history
        if (generation, length) != (h.generation, h.length) or outcome is None:
            return {}
        return {"verdict": outcome, "detail": words.lower()}

    def return_to_set_aside(self, number: int | None = None) -> None:
        """Enter a kept branch (the newest by default): replay its line from where it leaves the run's,
        then follow it (Step, Play) from there. The line left is kept as a branch in turn: none is lost."""
        with self.lock:
            number = self.branches.find(number).number  # the newest now, not once the line left is kept
            at, records = self.branches.path_to(number)
            e = self.engine
            self._playing = False
            e.seek(at)
            for record in records:
                if e.finished:
                    break
                self._branching_step(record.robots, record.round)
            entered = self.branches.entered(number)
            self.trace_events = e.state.events
            e.seek(entered.at)  # where the branch left: Step follows it from there
            self.following, self.following_what = True, f"branch #{entered.number}"
            self.trace_options = {}  # a trace's verdict describes the trace's line, not a branch

    def back_cycle(self) -> str:
        """Back over the whole Look-Compute-Move cycle of the robot that acted last: to just before its
        latest Look (its Move, Compute and Look undone together, and every step between them)."""
        with self.lock:
            self._playing = False
            e = self.engine
            if e.step_index == 0:
                return "at the start: nothing to undo"
            last = e.history.steps[e.step_index - 1].events
            robot = last[-1].robot
            for i in range(e.step_index - 1, -1, -1):
                if any(ev.robot == robot and ev.phase == "look" for ev in e.history.steps[i].events):
                    e.seek(i)
                    return f"back over robot {robot}'s cycle: to step {i}, before its Look"
            e.seek(0)
            return f"back to the start: robot {robot}'s cycle began there"

    def back(self) -> None:
        """Stop playing and take back the last step."""
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
            self._note_end()

    # ------------------------------------------------------------------ playing
    def play(self) -> None:
        """Play until paused or the run ends (nothing plays once it has ended)."""
        with self.lock:
            self._playing, self._stop_at = not self.engine.finished, None

    def play_to(self, step: int) -> None:
        """Play, and stop at ``step`` (a question's answer: workbench/poll.py)."""
        with self.lock:
            self._playing, self._stop_at = not self.engine.finished, step

    def pause(self) -> None:
        """Stop playing."""
        with self.lock:
            self._playing = False

    def toggle_play(self, beside: bool = False) -> None:
        """Play or pause; ``beside``: the run has ended but Compare's run beside it can go on alone, so
        Play plays that one (the session steps it)."""
        with self.lock:
            self._playing = not self._playing and (beside or not self.engine.finished)
            self._stop_at = None

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
            if self._stop_at is not None:
                allowance = min(allowance, self._stop_at - self.engine.step_index)
                if allowance <= 0:
                    self._playing, self._stop_at = False, None
                    return 0
            scheduler = self.config.scheduler
            if allowance >= 3 and not self.following and make_scheduler(scheduler).forced_when_alone:
                taken = self.engine.walk(allowance)  # Manual is never forced: the person chooses
                self._note_end()
                if taken:
                    return taken
            if not self.step():
                self._playing = False
                return 0
            return 1
