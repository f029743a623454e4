"""The visualiser's state: one shared run, the drafts being drawn, the mode, the selection, and what the
screen shows (:meth:`Session.view`).

No viser here, and no particular algorithm: what is drawn over the run (K, frames, targets, the stage)
and why a robot acted come from the algorithm's own description (:mod:`apf_viz.core.portrayal`). The
work is split by job: :class:`~apf_viz.ui.run_controller.RunController` (engine, adversary, play),
:class:`~apf_viz.ui.editor.Editor` (drafts), :mod:`apf_viz.ui.loader` (files in). Every call is
serialised by the run's lock, so all connected browsers drive the same run safely.
"""

from __future__ import annotations

import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from itertools import repeat
from typing import Literal, NamedTuple

import numpy as np

from apf_viz.algorithms import Factory
from apf_viz.core.algorithm import Decision
from apf_viz.core.budget import paper_D
from apf_viz.core.engine import NEXT_EVENT, Phase
from apf_viz.core.formats import (
    MAX_TRACE_BYTES,
    InputError,
    pattern_json,
    robots_json,
    size_problem,
    trace_text,
)
from apf_viz.core.frames import move_to_global, random_y_up
from apf_viz.core.grid import COORD_LIMIT, Point, short_int
from apf_viz.core.portrayal import (
    Band,
    Cells,
    Configuration,
    Explanation,
    Frame,
    HalfPlane,
    LightStyle,
    Line,
    Mark,
    Overlays,
    explain,
    in_frame,
    legend_of,
    overlays_of,
)
from apf_viz.core.run import trace_header
from apf_viz.core.schedule import Schedule, ScheduleError, follow, schedule_of_steps, schedule_text
from apf_viz.demos import pattern_of_size, scenarios
from apf_viz.ui import loader
from apf_viz.ui.compare import Twin
from apf_viz.ui.editor import Editor
from apf_viz.ui.run_config import RunConfig
from apf_viz.ui.run_controller import RunController
from apf_viz.ui.snapshot_diff import SeenRobot, seen_robots

Mode = Literal["run", "edit-pattern", "edit-robots"]
SCHEDULER_LABELS = {
    "FSYNC": "fsync",
    "SSYNC": "ssync",
    "ASYNC": "async",
    "stale-first": "stale-first",
    "round-robin": "round-robin",
    "Manual": "manual",
}


_PHASE_NAMES = ("idle", "looked", "computed")  # indexed by Phase
MAX_DIFFS = 8  # snapshot differences listed in the caption (the rest are counted)
NUMBERS_UP_TO = 50  # robots: numbers are on by default up to this many (beyond, they hide the run)
_COMPUTED = int(Phase.COMPUTED)


class RobotView(NamedTuple):
    """What the scene draws for one robot (a named tuple: a frame builds a thousand of them)."""

    position: Point
    light: str
    phase: str  # idle / looked / computed
    y_up: bool
    pending: Point | None  # global target of a computed move
    next_event: str


@dataclass(frozen=True)
class WhyView:
    """The selected robot's last decision and its evidence; regions already in the global frame."""

    robot: int
    explanation: Explanation | None  # None: the robot has not decided yet
    origin: Point  # where the robot stood when it looked (its frame's origin)
    regions: tuple[Mark, ...]
    holds_snapshot: bool  # it has looked again since (its next Compute will decide anew)
    changed: tuple[str, ...] = ()  # robots it saw that have since moved or changed light
    now: Decision | None = None  # what it would decide if it looked now


@dataclass(frozen=True)
class SessionView:
    """Everything the scene and panels show, computed in one place from the engine's state."""

    robots: tuple[RobotView, ...]
    targets: tuple[Point, ...]  # the cells of the overlays (or of the pattern being drawn)
    selected: int | None
    rays: tuple[tuple[Point, Point], ...]  # to what the selected robot saw (its snapshot) or sees now
    ghosts: tuple[tuple[Point, str], ...]  # where a robot was seen, with the light seen, if changed since
    overlays: Overlays
    legend: dict[str, LightStyle]
    why: WhyView | None
    outcome: str | None
    caption: str
    event: int
    steps: int
    history_length: int
    moves: int
    cycles: int
    stage: str
    lights_in_use: tuple[str, ...]
    moves_per_kD: float
    mode: Mode
    draft_count: int  # points of the pattern being drawn / robots being placed
    robot_count: int
    axis: float | None  # the unsolvable symmetry axis of the robots being edited, if any
    move_series: tuple[tuple[int, int], ...] = field(default=())
    skipped: int = 0  # robot·steps passed over because their next cycle could change nothing
    last_events: tuple[str, ...] = ()  # newest first, in words
    last_actor: int | None = None  # the robot of the last step (one robot: ASYNC or Manual)
    numbers: bool = False  # draw each robot's number beside it
    trace_position: tuple[int, int] | None = None  # (event, events in the trace) while following one
    collision: tuple[str, tuple[Point, ...]] | None = None  # what collided, in words, and the cells
    never_act: tuple[int, ...] = ()  # stuck: robots whose every future cycle changes nothing
    scenario_note: str = ""  # what the Demo scenario shown shows
    algorithm: str = ""  # the run's algorithm (by name)
    set_aside: tuple[int, int] | None = None  # a branch dropped recorded steps: (at step, how many)
    following_what: str = "the trace"  # what Step follows while trace_position is set
    click_advances: bool = True  # Manual: a click on a robot runs its next phase (else: selects only)
    compare: SessionView | None = None  # Compare: the same adversary under the second algorithm
    divergence: tuple[int, str] | None = None  # Compare: the first event where the two differ
    trace_note: str = ""  # what a loaded trace's header says it shows (a verdict, a gap, a loop)
    timeline_marks: tuple[tuple[int, str], ...] = ()  # steps of the timeline worth a mark (a loop)


class Session:
    """What every browser sees and drives: the run, the drafts, the mode and the selection."""

    def __init__(
        self,
        robots: Sequence[Point],
        pattern: Sequence[Point],
        *,
        y_up: Sequence[bool] | None = None,
        algorithm: str = "apf-opaque-grid",
        scheduler: str = "async",
        seed: int = 1,
        light_semantics: str = "compute",
        max_events: int = 5_000_000,
        plugins: Mapping[str, Factory] | None = None,
    ) -> None:
        problem = size_problem(len(pattern), len(robots))
        if problem:
            raise InputError(problem)
        flips = tuple(y_up) if y_up is not None else tuple(random_y_up(len(robots), seed))
        config = RunConfig(
            tuple(map(tuple, robots)),
            flips,
            tuple(map(tuple, pattern)),
            algorithm,
            light_semantics,  # type: ignore[arg-type]
            scheduler,
            seed,
            max_events,
        )
        self.run = RunController(config, plugins)
        self.lock = self.run.lock
        self.editor = Editor(config.robots, config.y_up, config.pattern)
        self.mode: Mode = "run"
        self.selected: int | None = None
        self.numbers: bool | None = None  # robot numbers on the canvas; None: on up to NUMBERS_UP_TO robots
        self.click_advances = True  # Manual: a click runs the robot's next phase; False: it only selects
        self.scenario_note = ""  # what the Demo scenario being shown shows, until another run starts
        self.twin: Twin | None = None  # Compare: a second algorithm stepping with the run

    # ------------------------------------------------------------------ the run, read-only
    @property
    def engine(self):
        return self.run.engine

    @property
    def config(self) -> RunConfig:
        return self.run.config

    @property
    def playing(self) -> bool:
        return self.run.playing

    @property
    def speed(self) -> float:
        return self.run.speed

    @property
    def scheduler_name(self) -> str:
        return self.run.config.scheduler

    @property
    def seed(self) -> int:
        return self.run.config.seed

    @property
    def algorithm_name(self) -> str:
        return self.run.config.algorithm

    @property
    def robots(self) -> list[Point]:
        return list(self.run.config.robots)

    @property
    def pattern(self) -> list[Point]:
        return list(self.run.config.pattern)

    @property
    def y_up(self) -> list[bool]:
        return list(self.run.config.y_up)

    # ------------------------------------------------------------------ building runs
    def _start(self, config: RunConfig) -> None:
        """A new run from ``config``; the drafts follow it and the selection is cleared."""
        self.run.restart(config)
        self.editor = Editor(config.robots, config.y_up, config.pattern)
        self.selected = None
        self.mode = "run"
        self.scenario_note = ""  # what a Demo scenario shows no longer applies

    def reset(self) -> None:
        """Back to the start of the current run (same start, pattern, flips, algorithm)."""
        with self.lock:
            self.run.reset()
            self.selected = None

    def set_algorithm(self, name: str) -> None:
        """The same start and pattern under another algorithm: the run restarts."""
        with self.lock:
            self.run.set_algorithm(name)
            self.selected = None

    def set_all_activations(self, keep: bool) -> None:
        """Keep every no-op activation (teaching what the adversary can do) or skip them (the default);
        the run restarts."""
        with self.lock:
            self.run.set_skip_noops(not keep)
            self.selected = None

    def set_light_semantics(self, semantics: str) -> None:
        with self.lock:
            self.run.set_light_semantics(semantics)
            self.selected = None

    # ------------------------------------------------------------------ stepping
    def step(self) -> bool:
        """One step chosen by the scheduler (in Manual: the selected robot). False if nothing ran."""
        with self.lock:
            if self.engine.finished or self.mode != "run":
                return False
            if self.scheduler_name == "manual" and not self.run.following:
                if self.selected is None:
                    return False
                self.run.step_robot(self.selected)
                return True
            return self.run.step()

    def why_not_step(self) -> str:
        """Why Step ran nothing, for the person who pressed it."""
        if self.mode != "run":
            return "Step runs in Run mode: switch Mode back to Run"
        if self.engine.finished:
            return f"the run is over ({self.engine.outcome}): Back, the timeline or Reset go on from earlier"
        if self.scheduler_name == "manual":
            return "Manual: click a robot to run its next phase"
        return "nothing could run"

    def play_step(self) -> bool:
        """One step of Play (the render thread's); stops playing when nothing ran."""
        with self.lock:
            if self.mode != "run":
                self.run.pause()
                return False
            return self.run.play_step()

    def run_until(self, what: Literal["move", "stage"], limit: int = 1_000_000, seconds: float = 3.0) -> str:
        """Step until some robot moves, or the stage changes; stops early on an outcome, in Manual, or
        after ``limit`` steps. Returns what happened, for a notification."""
        with self.lock:
            if self.mode != "run" or (self.scheduler_name == "manual" and not self.run.following):
                return "Next move / Next stage need a scheduler other than Manual"
            self.run.pause()
            e = self.engine
            wanted = "move" if what == "move" else "new stage"
            moves, stage = e.state.moves, self._overlays(e.current_points(), e.state.lights).stage
            version = e.state.version
            deadline = time.monotonic() + seconds  # the lock is held: keep every browser responsive
            for taken in range(1, limit + 1):
                if not self.run.step():
                    return f"the run is over ({e.outcome})" if e.finished else "nothing could run"
                if e.finished:
                    return f"{e.outcome} after {taken} steps"
                if what == "move" and e.state.moves > moves:
                    return f"a robot moved after {taken} steps"
                if what == "stage" and e.state.version != version:  # stages change with lights or moves
                    version = e.state.version
                    now = self._overlays(e.current_points(), e.state.lights).stage
                    if now != stage:
                        return f"{now} after {taken} steps"
                if time.monotonic() > deadline:
                    return f"still no {wanted} after {taken:,} steps: press again"
            return f"no {wanted} within {limit:,} steps"

    def back(self) -> None:
        self.run.back()

    def seek(self, step: float) -> None:
        """Stop playing and go to that step of the history (any number is clamped; NaN refused)."""
        self.run.seek(step)

    def set_scheduler(self, label_or_name: str) -> None:
        self.run.set_scheduler(SCHEDULER_LABELS.get(label_or_name, label_or_name))

    def set_seed(self, seed: float) -> None:
        self.run.set_seed(seed)

    def set_speed(self, speed: float) -> None:
        self.run.set_speed(speed)

    def toggle_play(self) -> None:
        with self.lock:
            if self.mode == "run":
                self.run.toggle_play()

    def pause(self) -> None:
        self.run.pause()

    # ------------------------------------------------------------------ clicks
    def robot_at(self, cell: Point) -> int | None:
        hits = np.flatnonzero((self.engine.positions == np.array(cell)).all(axis=1))
        return int(hits[0]) if hits.size else None

    def click(self, cell: Point) -> str:
        """A click on a grid cell, interpreted by the current mode. Returns what happened; a click outside
        the supported grid is refused (InputError)."""
        with self.lock:
            if abs(cell[0]) > COORD_LIMIT or abs(cell[1]) > COORD_LIMIT:
                raise InputError(
                    f"({short_int(cell[0])}, {short_int(cell[1])}) is outside the grid this tool supports "
                    f"(|x|, |y| ≤ {COORD_LIMIT:,})"
                )
            if self.mode == "edit-pattern":
                return self.editor.toggle_target(cell)
            if self.mode == "edit-robots":
                return self.editor.cycle_robot(cell)
            r = self.robot_at(cell)
            if r is None:
                self.selected = None
                return "nothing here"
            self.selected = r
            if self.scheduler_name == "manual" and self.click_advances and not self.engine.finished:
                return f"robot {r}: {self.run.step_robot(r)}"
            return f"selected robot {r}"

    def set_click_advances(self, advances: bool) -> None:
        """Manual: whether a click on a robot runs its next phase (advance) or only selects it, so that
        a student can read a robot's snapshot before choosing who acts."""
        with self.lock:
            self.click_advances = bool(advances)

    # ------------------------------------------------------------------ editing
    def set_mode(self, mode: Mode) -> str | None:
        """Switch modes. Leaving an edit mode validates the drafts and restarts the run; on a problem the
        mode stays, the drafts are kept, and the problem is returned (for the browser that asked)."""
        with self.lock:
            if mode == self.mode:
                return None
            if self.mode != "run" and mode == "run":
                problem = self.editor.problem()
                if problem:
                    return problem
                e = self.editor
                self._start(
                    self.config.but(robots=tuple(e.robots), y_up=tuple(e.y_up), pattern=tuple(e.pattern))
                )
                return None
            self.run.pause()
            self.mode = mode
            return None

    def clear_pattern(self) -> None:
        with self.lock:
            self.editor.clear_pattern()

    # ------------------------------------------------------------------ files
    def load_pattern(self, filename: str, content: bytes) -> str | None:
        """A pattern file; if its size fits the robots the run restarts with it, otherwise it becomes the
        pattern being drawn (Edit pattern), so nothing is lost; then what to do is returned."""
        points = tuple(tuple(p) for p in loader.pattern_upload(filename, content).points)
        with self.lock:
            if len(points) == len(self.config.robots):
                self._start(self.config.but(pattern=points))
                return None
            self.editor.pattern = list(points)
            self.run.pause()
            self.mode = "edit-pattern"
            return (
                f"{filename}: {len(points)} points for {len(self.config.robots)} robots: "
                "edit the pattern or the robots, then switch back to Run"
            )

    def load_robots(self, filename: str, content: bytes) -> str | None:
        """A robots file. If the current pattern has another size, a demo pattern of the robots' size
        is taken instead (the draft keeps the old one for Edit pattern), and said; an unsolvable start
        opens in Edit robots with its axis shown. Returns what to tell the person, if anything."""
        parsed = loader.robots_upload(filename, content)
        with self.lock:
            points = tuple(tuple(p) for p in parsed.robots)
            y_up = tuple(parsed.flips(self.seed))  # the same rule as every other way in (RobotsFile.flips)
            pattern, note = self.config.pattern, None
            if len(pattern) != len(points):
                offered = pattern_of_size(len(points))
                if offered is not None:
                    pattern = tuple(offered[1])
                    note = (
                        f"{filename}: {len(points)} robots, but the pattern had {len(self.config.pattern)} "
                        f"points: the run uses the demo pattern {offered[0]} ({len(points)} points); "
                        "Edit pattern or Upload pattern to change it"
                    )
            self.editor = Editor(points, y_up, pattern)
            problem = self.editor.problem()
            if problem is None:
                self._start(self.config.but(robots=points, y_up=y_up, pattern=pattern))
                return note
            self.run.pause()
            self.mode = "edit-robots"
            return f"{filename}: {problem}"

    def load_scenario(self, name: str) -> str:
        """A ready scenario by its name in the Demo list (never a path): its own algorithm, start and
        pattern (or trace) replace the run. Returns what it shows."""
        scenario = scenarios().get(name)
        if scenario is None:
            raise InputError(f"no demo called {name[:80]!r}")
        files = scenario.files()
        if "trace" in files:
            path = files["trace"]
            self.load_trace(path.name, path.read_bytes(), MAX_TRACE_BYTES)  # our own file
            self.scenario_note = scenario.shows
            return scenario.shows
        pattern = loader.pattern_upload(files["pattern"].name, files["pattern"].read_bytes())
        robots = loader.robots_upload(files["robots"].name, files["robots"].read_bytes())
        with self.lock:
            points = tuple(tuple(p) for p in robots.robots)
            y_up = tuple(robots.flips(self.seed))
            targets = tuple(tuple(p) for p in pattern.points)
            # A new run even on an unsolvable start, so that nothing of the previous run (a trace being
            # followed, an outcome) shows while its robots are edited; it is never stepped in Edit robots.
            config = self.config.but(robots=points, y_up=y_up, pattern=targets, algorithm=scenario.algorithm)
            self._start(config)
            problem = self.editor.problem()
            if problem:
                self.mode = "edit-robots"
            self.scenario_note = scenario.shows
        return scenario.shows + (f"  \n{problem}" if problem else "")

    def load_trace(self, filename: str, content: bytes, limit: int = loader.MAX_TRACE_UPLOAD_BYTES) -> None:
        """Replay a trace: checked event by event; the current run is untouched if it does not replay."""
        loaded = loader.trace_upload(filename, content, self.run.plugins, self.config.max_events, limit)
        h = loaded.header
        config = self.config.but(
            robots=tuple(map(tuple, h.robots)),
            y_up=tuple(loaded.engine.y_up),
            pattern=tuple(map(tuple, h.pattern)),
            algorithm=h.algorithm,
            light_semantics=h.light_semantics,
            scheduler=h.scheduler if h.scheduler in SCHEDULER_LABELS.values() else self.scheduler_name,
        )
        with self.lock:
            self.run.adopt(config, loaded.engine, loaded.events, h.options)
            self.scenario_note = ""
            self.editor = Editor(config.robots, config.y_up, config.pattern)
            self.mode = "run"
            self.selected = None

    def load_schedule(self, filename: str, content: bytes) -> str | None:
        """Replay a schedule file from the start of the current run (same start, pattern, algorithm);
        Step then follows it. A line that cannot be followed keeps the run up to it, and is returned."""
        schedule = loader.schedule_upload(filename, content)
        with self.lock:
            config, notes = _with_schedule_adversary(self.config, schedule, filename)
            engine = config.engine(self.run.plugins)
            try:
                for _ in follow(engine, schedule, filename):
                    pass
            except ScheduleError as e:
                notes.append(f"{e}; the run follows the schedule up to there")
            self.run.adopt(config, engine, engine.state.events, what=f"the schedule {filename}")
            self.editor = Editor(config.robots, config.y_up, config.pattern)
            self.scenario_note = ""
            self.mode = "run"
            self.selected = None
            return " ".join(notes) or None

    def schedule_file(self) -> str:
        """Who acted so far (Manual clicks included) and the flips, as a schedule file: the whole
        adversary, which drives any algorithm."""
        with self.lock:
            e = self.engine
            lines = schedule_of_steps(e.history.steps[: e.step_index])
            return schedule_text(e.k, lines, e.y_up, e.light_semantics)

    def robots_file(self) -> str:
        with self.lock:
            if self.mode == "edit-robots":
                return robots_json(self.editor.robots, self.editor.y_up)
            return robots_json(self.config.robots, self.config.y_up)

    def pattern_file(self) -> str:
        with self.lock:
            return pattern_json(self.editor.pattern if self.mode == "edit-pattern" else self.config.pattern)

    def trace_file(self) -> str:
        with self.lock:
            header = trace_header(self.engine, self.scheduler_name, self.seed)
            return trace_text(header, self.engine.history.events(self.engine.step_index))

    # ------------------------------------------------------------------ what to show
    def view(self) -> SessionView:
        with self.lock:
            return self._view()

    def _view(self) -> SessionView:
        e = self.engine
        st = e.state
        pts = e.current_points()
        robots = robot_views(e, pts)
        if self.mode == "edit-robots":  # the robots being placed, not the run's
            first = e.algorithm.lights[0]
            robots = [
                RobotView(p, first, "idle", up, None, "look")
                for p, up in zip(self.editor.robots, self.editor.y_up, strict=True)
            ]
        sel = self.selected if self.selected is not None and self.selected < e.k else None
        if self.mode != "run":
            sel = None
        rays: list[tuple[Point, Point]] = []
        ghosts: list[tuple[Point, str]] = []
        seen = seen_robots(e, sel, list(self.config.robots)) if sel is not None else []
        if sel is not None and st.snapshot[sel] is not None:  # what it saw, not what is there now
            rays = [(pts[sel], s.seen_at) for s in seen]
            ghosts = [(s.seen_at, s.seen_light) for s in seen if s.changed]
        elif sel is not None:
            rays = [(pts[sel], pts[j]) for j in e.visible(sel).tolist()]
        overlays = self._overlays(pts, st.lights)
        targets = next((m.points for m in overlays.marks if isinstance(m, Cells)), ())
        return SessionView(
            robots=tuple(robots),
            targets=targets,
            selected=sel,
            rays=tuple(rays),
            ghosts=tuple(ghosts),
            overlays=overlays,
            legend=legend_of(e.algorithm),
            why=self._why(sel, pts) if sel is not None else None,
            outcome=st.outcome,
            caption=self._caption(sel, seen),
            last_events=self._last_events(),
            trace_position=self.run.trace_position,
            last_actor=self._last_actor(),
            numbers=self.numbers if self.numbers is not None else len(robots) <= NUMBERS_UP_TO,
            collision=self._collision(pts) if st.outcome == "collision" and self.mode == "run" else None,
            never_act=tuple(range(e.k)) if st.outcome == "stuck" and self.mode == "run" else (),
            scenario_note=self.scenario_note,
            algorithm=self.algorithm_name,
            set_aside=(self.run.set_aside[0], len(self.run.set_aside[1])) if self.run.set_aside else None,
            following_what=self.run.following_what,
            click_advances=self.click_advances,
            compare=self._twin_view() if self.twin is not None and self.mode == "run" else None,
            divergence=self.twin.divergence(e) if self.twin is not None and self.mode == "run" else None,
            trace_note=trace_note(self.run.trace_options),
            timeline_marks=loop_marks(self.run.trace_options, e.history.length, self.config.scheduler),
            **run_numbers(e, overlays),
            mode=self.mode,
            draft_count=len(self.editor.pattern) if self.mode != "edit-robots" else len(self.editor.robots),
            robot_count=len(self.editor.robots) if self.mode == "edit-robots" else e.k,
            axis=self.editor.axis() if self.mode == "edit-robots" else None,
            move_series=self.run.series.at(e.history, e.step_index),
        )

    def compare_with(self, algorithm: str | None) -> None:
        """Compare: draw the same run (start, pattern, flips, adversary) under ``algorithm`` beside it,
        stepping with it; None stops comparing."""
        with self.lock:
            self.twin = Twin(algorithm, self.run.plugins) if algorithm else None

    def _twin_view(self) -> SessionView:
        """The second run as the scene draws it: robots, the algorithm's overlays, its outcome."""
        assert self.twin is not None
        t = self.twin.follow(self.engine, self.config)
        pts = t.current_points()
        st = t.state
        overlays = overlays_of(t.algorithm, Configuration(tuple(pts), tuple(st.lights), t.pattern, t.start))
        return SessionView(
            robots=tuple(robot_views(t, pts)),
            targets=next((m.points for m in overlays.marks if isinstance(m, Cells)), ()),
            selected=None,
            rays=(),
            ghosts=(),
            overlays=overlays,
            legend=legend_of(t.algorithm),
            why=None,
            outcome=st.outcome,
            caption="",
            **run_numbers(t, overlays),
            mode="run",
            draft_count=len(t.pattern),
            robot_count=t.k,
            axis=None,
            numbers=self.numbers if self.numbers is not None else t.k <= NUMBERS_UP_TO,
            collision=None,
            never_act=tuple(range(t.k)) if st.outcome == "stuck" else (),
            algorithm=self.twin.algorithm,
        )

    def branch_here(self) -> None:
        """Stop following a loaded trace: from this event on, the chosen scheduler runs."""
        self.run.branch_here()

    def return_to_set_aside(self) -> None:
        """Back to the recorded steps the last branch dropped; Step then follows them."""
        self.run.return_to_set_aside()

    def set_numbers(self, on: bool) -> None:
        with self.lock:
            self.numbers = bool(on)

    def _collision(self, pts: list[Point]) -> tuple[str, tuple[Point, ...]] | None:
        """The colliding moves of the last step, in words, and the cells involved."""
        e = self.engine
        if e.step_index == 0:
            return None
        st = e.state
        movers = [ev for ev in e.history.steps[e.step_index - 1].events if ev.collision]
        where = {p: i for i, p in enumerate(pts)}
        words, cells = [], []
        for ev in movers:
            other = where.get(ev.to)
            onto = f"onto robot {other}" if other is not None and other != ev.robot else "into another mover"
            words.append(
                f"robot {ev.robot} moved {onto} at ({ev.to[0]}, {ev.to[1]}) on a snapshot taken at step "
                f"{int(st.look_step[ev.robot])}"
            )
            cells += [ev.to, pts[ev.robot]]
        return ("; ".join(words), tuple(dict.fromkeys(cells))) if words else None

    def _last_actor(self) -> int | None:
        e = self.engine
        if e.step_index == 0 or self.mode != "run":
            return None
        events = e.history.steps[e.step_index - 1].events
        return events[-1].robot if len(events) == 1 else None

    def _overlays(self, pts: list[Point], lights: list[str]) -> Overlays:
        """The algorithm's marks over the run; while a pattern is drawn, that pattern's cells instead, and
        while robots are placed, the pattern they will be given (the draft's, not the run's)."""
        if self.mode == "edit-pattern":
            return Overlays(
                (Cells(tuple(self.editor.pattern), "pattern being drawn"),), "editing the pattern"
            )
        if self.mode == "edit-robots":
            return Overlays(
                (Cells(tuple(self.editor.pattern), "pattern for these robots", "preview"),),
                "editing the robots",
            )
        config = Configuration(tuple(pts), tuple(lights), self.config.pattern, self.config.robots)
        return overlays_of(self.engine.algorithm, config)

    def _why(self, r: int, pts: list[Point]) -> WhyView:
        """Robot r's last decision, explained from the snapshot it was computed on (the evidence is the
        evidence), and its regions placed in the global frame where the robot stood at that Look."""
        st = self.engine.state
        view = st.decided[r]
        holds = st.phase[r] == Phase.LOOKED
        if view is None:
            return WhyView(r, None, pts[r], (), holds)
        explained = explain(self.engine.algorithm, view, self.engine.pattern)
        up = self.config.y_up[r]
        x, y = pts[r]
        if st.phase[r] != Phase.COMPUTED and explained.decision.move is not None:
            dx, dy = move_to_global(explained.decision.move, up).delta  # it has moved since that Look
            x, y = x - dx, y - dy
        regions = tuple(_to_global(m, (x, y), up) for m in explained.regions)
        now = self.engine.decide(self.engine.look(r))  # what it would decide on the present view
        return WhyView(
            r, explained, (x, y), regions, holds, self._changed_since(view, (x, y), up, pts, st.lights), now
        )

    @staticmethod
    def _changed_since(view, origin: Point, up: bool, pts: list[Point], lights: list[str]) -> tuple[str, ...]:
        """The robots a snapshot saw that are no longer where it saw them, or show another light now."""
        now = dict(zip(pts, lights, strict=True))
        out = []
        for seen, p in zip(view.robots, in_frame(view.offsets(), origin, up), strict=True):
            light = now.get(p)
            if light is None:
                out.append(f"seen at ({p[0]}, {p[1]}) with light {seen.light}: gone from there")
            elif light != seen.light:
                out.append(f"seen at ({p[0]}, {p[1]}) with light {seen.light}: now {light}")
        return tuple(out)

    def _caption(self, sel: int | None, seen: list[SeenRobot]) -> str:
        if sel is None:
            return "Click a robot to see what it sees and why it acts."
        e = self.engine
        st = e.state
        phase = ("idle", "looked", "computed")[st.phase[sel]]
        lines = [
            f"**Robot {sel}** — light `{st.lights[sel]}`, {phase}; next: {e.next_event(sel)}; "
            f"y-axis {'up' if self.config.y_up[sel] else 'flipped'}",
        ]
        if st.snapshot[sel] is None:
            lines.append(f"Idle: rays show the {len(e.visible(sel))} robots it would see if it looked now.")
            return "\n\n".join(lines)
        look = (
            f"its snapshot from step {int(st.look_step[sel])} ({len(seen)} robots; rays go where it saw them)"
        )
        changed = [s.describe() for s in seen if s.changed]
        if not changed:
            lines.append(f"It holds {look}. Nothing it saw has changed since: the snapshot is current.")
            return "\n\n".join(lines)
        shown = changed[:MAX_DIFFS]
        more = f"  \n… and {len(changed) - len(shown)} more" if len(changed) > len(shown) else ""
        lines.append(
            f"It holds {look}. **Stale**: {len(changed)} of them changed since (ghosts, in the light it "
            "saw, mark where):  \n" + "  \n".join(f"· {c}" for c in shown) + more
        )
        return "\n\n".join(lines)

    # ------------------------------------------------------------------ what just happened
    def _last_events(self, n: int = 8) -> tuple[str, ...]:
        """The last ``n`` events, newest first, in words: who did what."""
        e = self.engine
        st = e.state
        out: list[str] = []
        first = max(0, e.step_index - n)
        window = e.history.steps[first : e.step_index]
        latest_seen: set[int] = set()
        for step in reversed(window):
            for ev in reversed(step.events):
                stays = False
                if ev.phase == "move" and ev.robot not in latest_seen and st.decided[ev.robot] is not None:
                    # Its latest event: the decision it moved on is the one on its latest decided snapshot.
                    stays = e.decide(st.decided[ev.robot]).move is None
                latest_seen.add(ev.robot)
                out.append(describe_event(ev, stays))
                if len(out) == n:
                    return tuple(out)
        return tuple(out)


def robot_views(e, pts: list[Point]) -> list[RobotView]:
    """What the scene draws for each robot of engine ``e`` (``pts``: its current points)."""
    st = e.state
    phases = st.phase.tolist()
    pending: list[Point | None] = [None] * e.k
    for r in np.flatnonzero(st.phase == _COMPUTED).tolist():
        if st.pending[r].move is not None:
            dx, dy = move_to_global(st.pending[r].move, e.y_up[r]).delta
            pending[r] = (pts[r][0] + dx, pts[r][1] + dy)
    # tuple.__new__ mapped in C: a thousand robots a frame, and a NamedTuple's __new__ is Python.
    return list(
        map(
            tuple.__new__,
            repeat(RobotView),
            zip(
                pts,
                st.lights,
                [_PHASE_NAMES[p] for p in phases],
                e.y_up,
                pending,
                [NEXT_EVENT[p] for p in phases],
                strict=True,
            ),
        )
    )


def run_numbers(e, overlays: Overlays) -> dict:
    """The counts and stage a panel shows for engine ``e`` (the run's, or Compare's second run)."""
    st = e.state
    return {
        "event": st.events,
        "steps": st.steps,
        "history_length": e.history.length,
        "moves": st.moves,
        "cycles": st.cycles,
        "stage": overlays.stage,
        "lights_in_use": tuple(sorted(set(st.lights), key=e.algorithm.lights.index)),
        "skipped": st.skipped,
        "moves_per_kD": st.moves / (e.k * paper_D(e.start, e.pattern)),
    }


def trace_note(options: Mapping[str, object]) -> str:
    """What a trace's header says it shows, in one line ("" for a plain recorded run)."""
    verdict = options.get("verdict") or options.get("literal_failure")
    detail = options.get("detail")
    problems = options.get("problems")
    if not detail and isinstance(problems, list) and problems:
        detail = str(problems[0])
    gap = options.get("shows_gap")
    parts = []
    if gap:
        parts.append(f"shows gap {gap} (the variant without its resolution)")
    if verdict:
        detail = str(detail or "").removeprefix(f"{verdict}: ")
        parts.append(f"verdict: {verdict}" + (f" — {detail}" if detail and detail != verdict else ""))
    return "; ".join(parts)


def loop_marks(options: Mapping[str, object], steps: int, scheduler: str) -> tuple[tuple[int, str], ...]:
    """A livelock from ``apf-viz check``: the header gives the explorer step where the loop begins, and
    the trace runs the loop twice; marks where it begins, repeats and ends, in engine steps (a
    synchronous explorer step is three engine steps: Looks, Computes, Moves)."""
    start = options.get("loop_starts_at_step")
    if not isinstance(start, int) or isinstance(start, bool) or start < 0:
        return ()
    per = 1 if scheduler in ("async", "manual", "stale-first", "round-robin") else 3
    items = steps // per
    if items <= start:
        return ()
    twice = (items - start) // 2
    first, again = start * per, (start + twice) * per
    return ((first, "loop starts"), (again, "loop repeats"), (again + twice * per, "…for ever"))


def describe_event(ev, stays: bool = False) -> str:
    """One event in words: "robot 3 · Move → (1, 0)", "robot 1 · Compute → light leader1, stay — A1.off.on-K"
    (``stays``: the Move of a decision to stay)."""
    head = f"robot {ev.robot} · "
    if ev.phase == "look":
        return head + f"Look: sees {len(ev.sees or ())} robots"
    if ev.phase == "compute":
        move = f", move {ev.move.value}" if ev.move is not None else ", stay"
        rule = f" — {ev.rule_id or ev.rule}" if (ev.rule_id or ev.rule) else ""
        return head + f"Compute → light {ev.light}{move}{rule}"
    if ev.collision:
        return head + f"Move → ({ev.to[0]}, {ev.to[1]}): COLLISION"
    if stays:
        return head + f"Move: stays at ({ev.to[0]}, {ev.to[1]})"
    return head + f"Move → ({ev.to[0]}, {ev.to[1]})"


def _with_schedule_adversary(
    config: RunConfig, schedule: Schedule, filename: str
) -> tuple[RunConfig, list[str]]:
    """The run a schedule replays: the current start and pattern with the schedule's flips and light
    semantics (a version-1 schedule has none: the run's own are kept, and the notes say so)."""
    if schedule.k != len(config.robots):
        return config, []  # follow() refuses it in one line before any step
    notes: list[str] = []
    if schedule.y_up is None:
        notes.append(f"{filename} records no y-axis flips: the run's own are kept.")
    elif schedule.y_up != config.y_up:
        flipped = sum(a != b for a, b in zip(schedule.y_up, config.y_up, strict=True))
        notes.append(f"The schedule's y-axis flips replace the run's ({flipped} robots differ).")
        config = config.but(y_up=schedule.y_up)
    if schedule.light_semantics and schedule.light_semantics != config.light_semantics:
        notes.append(f"The schedule was recorded under {schedule.light_semantics}: the run now uses it.")
        config = config.but(light_semantics=schedule.light_semantics)
    return config, notes


def _to_global(mark: Mark, origin: Point, y_up: bool) -> Mark:
    """A mark in a robot's own frame (the robot at (0, 0), its own +y up) in the global frame."""
    ox, oy = origin
    s = 1 if y_up else -1
    if isinstance(mark, Line):
        return Line(mark.axis, ox + mark.at if mark.axis == "x" else oy + s * mark.at, mark.label)
    if isinstance(mark, Band):
        if mark.axis == "x":
            return Band("x", ox + mark.lo, ox + mark.hi, mark.label)
        lo, hi = sorted((oy + s * mark.lo, oy + s * mark.hi))
        return Band("y", lo, hi, mark.label)
    if isinstance(mark, HalfPlane):
        if mark.axis == "x":
            return HalfPlane("x", ox + mark.at, mark.side, mark.closed, mark.label)
        return HalfPlane("y", oy + s * mark.at, mark.side * s, mark.closed, mark.label)  # type: ignore[arg-type]
    if isinstance(mark, Frame):
        return Frame((ox + mark.origin[0], oy + s * mark.origin[1]), mark.y_sign * s, mark.label)
    return Cells(in_frame(mark.points, origin, y_up), mark.label, mark.style)
