"""The visualiser's commands: one shared run, the drafts being drawn, the mode, and each connected
browser's own state (its selection). What the screen shows is the view model's (:mod:`apf_viz.ui.view_model`):
:meth:`Session.view` asks it, for one browser, under the run's lock.

No viser here, and no particular algorithm. The work is split by job:
:class:`~apf_viz.ui.run_controller.RunController` (engine, adversary, play),
:class:`~apf_viz.ui.editor.Editor` (drafts), :mod:`apf_viz.ui.loader` (files in),
:mod:`apf_viz.ui.screen_state` (the screen's state, shared and per browser). Every call is serialised by
the run's lock, so all connected browsers drive the same run safely.
"""

from __future__ import annotations

import time
from collections.abc import Hashable, Mapping, Sequence
from typing import Literal

import numpy as np

from apf_viz.algorithms import DEFAULT_ALGORITHM, Factory
from apf_viz.core import shapes
from apf_viz.core.formats import (
    MAX_TRACE_BYTES,
    InputError,
    pattern_json,
    robots_json,
    size_problem,
    trace_text,
)
from apf_viz.core.frames import random_y_up
from apf_viz.core.grid import COORD_LIMIT, Point, as_point, short_int
from apf_viz.core.run import trace_header
from apf_viz.core.schedule import Schedule, ScheduleError, follow, schedule_of_steps, schedule_text
from apf_viz.core.schedulers import REGISTRY as SCHEDULER_REGISTRY
from apf_viz.demos import pattern_of_size, scenarios
from apf_viz.lecture import Lecture
from apf_viz.ui import loader
from apf_viz.ui.compare import Twin
from apf_viz.ui.editor import Editor, draft_of
from apf_viz.ui.lecturer import Lecturer, Reached
from apf_viz.ui.library import PatternLibrary
from apf_viz.ui.run_config import RunConfig
from apf_viz.ui.run_controller import RunController
from apf_viz.ui.screen_state import BrowserState, LectureStop, Mode, SharedScreen
from apf_viz.ui.view_model import SessionView, for_browser, present, present_run, stage_of
from apf_viz.ui.view_model.story import MAX_TRAIL

SCHEDULER_LABELS = {kind.label: kind.name for kind in SCHEDULER_REGISTRY}
"""The UI's dropdown: each scheduler's label, and the name it stands for (core/schedulers)."""


def _screen_field(name: str) -> property:
    """A Session attribute that is the shared screen's field ``name`` (read and written)."""
    return property(
        lambda self: getattr(self.screen, name), lambda self, value: setattr(self.screen, name, value)
    )


class Session:
    """What every browser sees and drives: the run, the drafts, the mode and the selection."""

    def __init__(
        self,
        robots: Sequence[Point],
        pattern: Sequence[Point],
        *,
        y_up: Sequence[bool] | None = None,
        algorithm: str = DEFAULT_ALGORITHM,
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
            tuple(map(as_point, robots)),
            flips,
            tuple(map(as_point, pattern)),
            algorithm,
            light_semantics,  # type: ignore[arg-type]
            scheduler,
            seed,
            max_events,
        )
        self.run = RunController(config, plugins)
        self.lock = self.run.lock
        self.screen = SharedScreen(Editor(config.robots, config.y_up, config.pattern))
        self.kept_drafts = False  # a load replaced drafts never run (:meth:`take_kept_drafts_note`)
        # The presenter's browser state: the first browser to connect holds it (the projector), and so
        # do the calls made without a browser (scripts, tests). Other browsers get their own.
        self.presenter = BrowserState()
        self._browsers: dict[Hashable, BrowserState] = {}
        self._presenter_of: Hashable | None = None
        self.lecturer: Lecturer | None = None  # a guided lecture being followed (PageDown: its next stop)
        self.library = PatternLibrary()  # saved patterns (serve --library chooses the folder)
        self.saved = self.library.names()  # their names, read once and after each save

    # ------------------------------------------------------------------ browsers
    def join(self, browser: Hashable) -> BrowserState:
        """A browser connects: the first one (or the first after the presenter left) presents."""
        with self.lock:
            if self._presenter_of is None:
                self._presenter_of = browser
                state = self.presenter
            else:
                state = BrowserState()
            self._browsers[browser] = state
            return state

    def leave(self, browser: Hashable) -> None:
        with self.lock:
            self._browsers.pop(browser, None)
            if browser == self._presenter_of:
                self._presenter_of = None  # the next browser to connect presents (a reloaded projector)

    def browser(self, browser: Hashable | None) -> BrowserState:
        """That browser's state (the presenter's for None or an unknown browser)."""
        return self._browsers.get(browser, self.presenter) if browser is not None else self.presenter

    def is_presenter(self, browser: Hashable | None) -> bool:
        return self.browser(browser) is self.presenter

    def _clear_selections(self) -> None:
        self.presenter.selected = None
        for state in self._browsers.values():
            state.selected = None

    # ------------------------------------------------------------------ the screen, shared
    editor = _screen_field("editor")
    mode = _screen_field("mode")
    scenario_note = _screen_field("scenario_note")
    twin = _screen_field("twin")
    click_advances = _screen_field("click_advances")
    numbers = _screen_field("numbers")

    @property
    def selected(self) -> int | None:
        """The presenter's selected robot (scripts and tests select through it)."""
        return self.presenter.selected

    @selected.setter
    def selected(self, robot: int | None) -> None:
        self.presenter.selected = robot

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
        self._drafts_follow(config)
        self.run.restart(config)
        self._clear_selections()
        self.mode = "run"
        self.scenario_note = ""  # what a Demo scenario shows no longer applies

    def _drafts_follow(self, config: RunConfig) -> None:
        """The drafts become ``config``'s start and pattern, the old ones kept for Undo; drafts that the
        run did not have (drawn, not yet run) are noted in :attr:`kept_drafts` for the browser to be
        told."""
        e, now = self.editor, self.run.config
        unrun = e.draft != draft_of(now.robots, now.y_up, now.pattern)
        # No change when the run starts from the drafts themselves (Mode back to Run).
        if e.start_from(config.robots, config.y_up, config.pattern):
            self.kept_drafts = self.kept_drafts or unrun

    def take_kept_drafts_note(self) -> str | None:
        """Once, after a load replaced drafts that had not been run: how to get them back."""
        kept, self.kept_drafts = self.kept_drafts, False
        if not kept:
            return None
        return "what you drew in Edit is kept: in the Edit folder, Undo brings it back"

    def reset(self) -> None:
        """Back to the start of the current run (same start, pattern, flips, algorithm)."""
        with self.lock:
            self.run.reset()
            self._clear_selections()

    def set_algorithm(self, name: str) -> None:
        """The same start and pattern under another algorithm: the run restarts."""
        with self.lock:
            self.run.set_algorithm(name)
            self._clear_selections()

    def set_all_activations(self, keep: bool) -> None:
        """Keep every no-op activation (teaching what the adversary can do) or skip them (the default);
        the run restarts."""
        with self.lock:
            self.run.set_skip_noops(not keep)
            self._clear_selections()

    def set_light_semantics(self, semantics: str) -> None:
        with self.lock:
            self.run.set_light_semantics(semantics)
            self._clear_selections()

    # ------------------------------------------------------------------ stepping
    def step(self, browser: Hashable | None = None) -> bool:
        """One step chosen by the scheduler (in Manual: the robot that browser selected). False if
        nothing ran."""
        with self.lock:
            if self.engine.finished or self.mode != "run":
                return False
            if self.scheduler_name == "manual" and not self.run.following:
                selected = self.browser(browser).selected
                if selected is None:
                    return False
                self.run.step_robot(selected)
                return True
            return self.run.step()

    def why_not_step(self) -> str:
        """Why Step ran nothing, for the person who pressed it."""
        if self.mode != "run":
            return self._why_editing("Step")
        if self.engine.finished:
            said = f"the run is over ({self.engine.outcome}): Back, the timeline or Reset go on from earlier"
            twin = self.screen.twin.engine if self.screen.twin is not None else None
            if twin is not None:  # Compare: the run beside it replays this run's steps, and there are no more
                at, state = twin.state.events, twin.outcome or "running"
                said += f"; the run beside it stands at event {at}, {state}, with no steps left"
            return said
        if self.scheduler_name == "manual":
            return "Manual: click a robot to run its next phase"
        return "nothing could run"

    def play_steps(self, allowance: int = 1) -> int:
        """Up to ``allowance`` steps of Play (the render thread's); stops playing when nothing ran.
        Returns the steps taken (0: none)."""
        with self.lock:
            if self.mode != "run":
                self.run.pause()
                return 0
            return self.run.play_steps(allowance)

    def run_until(self, what: Literal["move", "stage"], limit: int = 1_000_000, seconds: float = 3.0) -> str:
        """Step until some robot moves, or the stage changes; stops early on an outcome, in Manual, or
        after ``limit`` steps. Returns what happened, for a notification."""
        with self.lock:
            if self.mode != "run":  # e.g. the Unsolvable box demo opens in Edit robots
                return self._why_editing("Next move / Next stage")
            if self.scheduler_name == "manual" and not self.run.following:
                return "Next move / Next stage need a scheduler other than Manual"
            self.run.pause()
            e = self.engine
            wanted = "move" if what == "move" else "new stage"
            moves, stage = e.state.moves, stage_of(self.run, self.screen)
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
                    now = stage_of(self.run, self.screen)
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

    def seek_event(self, event: int) -> None:
        """Go to the step that ends with event number ``event`` (Compare's Go to divergence)."""
        with self.lock:
            done = 0
            history = self.engine.history
            for i, effects in enumerate(history.effects(0, history.length)):
                done += len(effects)
                if done >= event:
                    self.run.seek(i + 1)
                    return
            self.run.seek(self.engine.history.length)

    def back_to_stage(self, seconds: float = 3.0) -> str:
        """Back to where the previous stage began (PageUp: Next stage's stops, in reverse). Returns what
        happened, for a notification."""
        with self.lock:
            self.run.pause()
            e = self.engine
            deadline = time.monotonic() + seconds  # the lock is held: keep every browser responsive
            if e.step_index == 0:
                return "at the start of the run"
            stage = stage_of(self.run, self.screen)
            while e.step_index > 0 and stage_of(self.run, self.screen) == stage:
                e.seek(e.step_index - 1)  # into the previous stage (or to the start)
                if time.monotonic() > deadline:
                    return f"still in {stage} at step {e.step_index}: press again"
            previous = stage_of(self.run, self.screen)
            while e.step_index > 0:
                e.seek(e.step_index - 1)
                if stage_of(self.run, self.screen) != previous:
                    e.seek(e.step_index + 1)  # its first step
                    break
                if time.monotonic() > deadline:
                    break
            return f"{previous} from step {e.step_index}"

    def set_scheduler(self, label_or_name: str) -> None:
        self.run.set_scheduler(SCHEDULER_LABELS.get(label_or_name, label_or_name))

    def set_seed(self, seed: float) -> None:
        self.run.set_seed(seed)

    def set_speed(self, speed: float) -> None:
        self.run.set_speed(speed)

    def toggle_play(self) -> str | None:
        """Play or pause; in an edit mode nothing plays, and why is returned (for the browser that
        asked): the drafts' problem if they have one, else the way back to Run."""
        with self.lock:
            if self.mode != "run":
                return self._why_editing("Play")
            self.run.toggle_play()
            return None

    def _why_editing(self, control: str) -> str:
        problem = self.editor.problem()
        if problem:  # e.g. the Unsolvable box demo: Run would refuse the drafts as they are
            return f"{control} runs in Run mode, and these drafts cannot start a run: {problem}"
        return f"{control} runs in Run mode: switch Mode back to Run"

    def pause(self) -> None:
        self.run.pause()

    # ------------------------------------------------------------------ clicks
    def robot_at(self, cell: Point) -> int | None:
        hits = np.flatnonzero((self.engine.positions == np.array(cell)).all(axis=1))
        return int(hits[0]) if hits.size else None

    def click(self, cell: Point, browser: Hashable | None = None) -> str:
        """A click on a grid cell by one browser, interpreted by the current mode: in Run it selects the
        robot there for that browser (and in Manual runs its next phase). Returns what happened; a click
        outside the supported grid is refused (InputError)."""
        with self.lock:
            if abs(cell[0]) > COORD_LIMIT or abs(cell[1]) > COORD_LIMIT:
                raise InputError(
                    f"({short_int(cell[0])}, {short_int(cell[1])}) is outside the grid this tool supports "
                    f"(|x|, |y| ≤ {COORD_LIMIT:,})"
                )
            if self.mode != "run":
                return self.screen.studio.click(self.editor, self.mode, cell)
            r = self.robot_at(cell)
            state = self.browser(browser)
            if r is None:
                state.selected = None
                return "nothing here"
            state.selected = r
            if self.scheduler_name == "manual" and self.click_advances and not self.engine.finished:
                return f"robot {r}: {self.run.step_robot(r)}"
            return f"selected robot {r}"

    def set_click_advances(self, advances: bool) -> None:
        """Manual: whether a click on a robot runs its next phase (advance) or only selects it, so that
        a student can read a robot's snapshot before choosing who acts."""
        with self.lock:
            self.screen.click_advances = bool(advances)

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
            if mode == "edit-pattern":
                self._place_draft_beside_robots()
            self.mode = mode
            return None

    def _place_draft_beside_robots(self) -> None:
        """Move the drawn pattern beside the robots (a pattern is a shape: where it is drawn does not
        matter), where the run shows it before a leader places it, so it is framed with them and never
        drawn over them."""
        e = self.editor
        if not e.pattern or not e.robots:
            return
        dx = max(x for x, _ in e.robots) + 3 - min(x for x, _ in e.pattern)
        dy = min(y for _, y in e.robots) - min(y for _, y in e.pattern)
        if dx or dy:
            e.pattern = shapes.translated(e.pattern, dx, dy)

    def clear_pattern(self) -> None:
        with self.lock:
            self.editor.clear_pattern()

    def use_library(self, library: PatternLibrary) -> None:
        with self.lock:
            self.library, self.saved = library, library.names()

    def save_pattern(self, name: str) -> str:
        """The pattern being drawn (in Run: the run's) saved under ``name`` in the library."""
        with self.lock:
            cells = self.editor.pattern if self.mode == "edit-pattern" else list(self.config.pattern)
            path = self.library.save(name, cells)
            self.saved = self.library.names()
            return f"saved {len(cells)} cells as {name.strip()!r} ({path})"

    def load_saved_pattern(self, name: str) -> str:
        """A saved pattern becomes the pattern being drawn (Edit pattern), beside the robots."""
        cells = self.library.load(name)
        with self.lock:
            self.run.pause()
            said = self.editor.set_pattern(
                cells, f"loaded {name!r}: {len(cells)} cells for {self.engine.k} robots"
            )
            self.mode = "edit-pattern"
            self._place_draft_beside_robots()
            return said

    # ------------------------------------------------------------------ the pattern studio
    def set_tool(self, tool: str) -> None:
        with self.lock:
            self.screen.studio.choose(tool)

    def set_tool_size(self, size: float) -> None:
        """The size of a placed shape (a ring's radius, a row's length): a whole number 1 .. 200."""
        if (
            not isinstance(size, int | float)
            or size != size
            or not float(size).is_integer()
            or not 1 <= size <= 200
        ):
            raise InputError(f"size {size!r}: choose a whole number from 1 to 200")
        with self.lock:
            self.screen.studio.size = int(size)

    def set_tool_text(self, text: str) -> None:
        shapes.text(text, (0, 0))  # refuses a character the font has not, before anything changes
        with self.lock:
            self.screen.studio.text = text

    def draw_box(self, a: Point, b: Point, erase: bool) -> str:
        """A box dragged in an edit mode: filled, or (``erase``) emptied."""
        with self.lock:
            for cell in (a, b):
                if abs(cell[0]) > COORD_LIMIT or abs(cell[1]) > COORD_LIMIT:
                    raise InputError(
                        f"{cell} is outside the grid this tool supports (|x|, |y| ≤ {COORD_LIMIT:,})"
                    )
            if self.mode == "run":
                return "drag a box in Edit pattern or Edit robots"
            return self.screen.studio.box(self.editor, self.mode, a, b, erase)

    def transform(self, name: str) -> str:
        """Mirror, rotate, scale or fit the draft being edited; Undo and Redo."""
        with self.lock:
            if self.mode == "run":
                return "transforms change a draft: choose Edit pattern or Edit robots"
            if name == "Undo":
                return self.editor.undo()
            if name == "Redo":
                return self.editor.redo()
            return self.screen.studio.transform(self.editor, self.mode, name)

    # ------------------------------------------------------------------ files
    def load_pattern(self, filename: str, content: bytes) -> str | None:
        """A pattern file; if its size fits the robots the run restarts with it, otherwise it becomes the
        pattern being drawn (Edit pattern), so nothing is lost; then what to do is returned."""
        points = tuple(as_point(p) for p in loader.pattern_upload(filename, content).points)
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
            points = tuple(as_point(p) for p in parsed.robots)
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
            self._drafts_follow(self.config.but(robots=points, y_up=y_up, pattern=pattern))
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
            points = tuple(as_point(p) for p in robots.robots)
            y_up = tuple(robots.flips(self.seed))
            targets = tuple(as_point(p) for p in pattern.points)
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
            self._drafts_follow(config)
            self.run.adopt(config, loaded.engine, loaded.events, h.options)
            self.scenario_note = ""
            self.mode = "run"
            self._clear_selections()

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
            self._drafts_follow(config)
            self.run.adopt(config, engine, engine.state.events, what=f"the schedule {filename}")
            self.scenario_note = ""
            self.mode = "run"
            self._clear_selections()
            return " ".join(notes) or None

    def schedule_file(self) -> str:
        """Who acted so far (Manual clicks included) and the flips, as a schedule file: the whole
        adversary, which drives any algorithm."""
        with self.lock:
            e = self.engine
            lines = schedule_of_steps(e.history.steps.between(0, e.step_index))
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
    def view(self, browser: Hashable | None = None) -> SessionView:
        """What that browser shows (the presenter's view for None)."""
        with self.lock:
            return present(self.run, self.screen, self.browser(browser), self.presenter)

    def views(self, browsers: Sequence[Hashable]) -> tuple[SessionView, dict[Hashable, SessionView]]:
        """The run's view (what every browser shares) and each browser's, made at one instant: the
        run's part once, each browser's selection laid over it."""
        with self.lock:
            shared = present_run(self.run, self.screen)
            own = {
                b: for_browser(shared, self.run, self.screen, self.browser(b), self.presenter)
                for b in browsers
            }
            return shared, own

    def set_follow(self, browser: Hashable | None, follow: bool) -> None:
        """That browser shows the presenter's selection (True) or its own (False)."""
        with self.lock:
            self.browser(browser).follow = bool(follow)

    def compare_with(self, algorithm: str | None) -> None:
        """Compare: draw the same run (start, pattern, flips, adversary) under ``algorithm`` beside it,
        stepping with it; None stops comparing."""
        with self.lock:
            self.screen.twin = Twin(algorithm, self.run.plugins) if algorithm else None

    def branch_here(self) -> None:
        """Stop following a loaded trace: from this event on, the chosen scheduler runs."""
        self.run.branch_here()

    def return_to_set_aside(self) -> None:
        """Back to the recorded steps the last branch dropped; Step then follows them."""
        self.run.return_to_set_aside()

    # ------------------------------------------------------------------ a guided lecture
    def start_lecture(self, lecture: Lecture | None) -> str:
        """Follow ``lecture`` (None: stop following one) from its first stop."""
        self.lecturer = Lecturer(self, lecture) if lecture is not None else None
        self.screen.lecture = None
        return self.next_stop() if lecture is not None else "no lecture: PageDown stops at the run's stages"

    def load_lecture(self, filename: str, content: bytes) -> str:
        """A lecture file uploaded (checked whole first: a bad one leaves the run and lecture as they are)."""
        return self.start_lecture(loader.lecture_upload(filename, content))

    def next_stop(self) -> str:
        """The lecture's next stop (PageDown): run to its condition; what happened, for a notification."""
        if self.lecturer is None:
            return "no lecture loaded"
        return self._at_stop(self.lecturer.next(), "the lecture's last stop")

    def previous_stop(self) -> str:
        if self.lecturer is None:
            return "no lecture loaded"
        return self._at_stop(self.lecturer.previous(), "the lecture's first stop")

    def _at_stop(self, reached: Reached | None, edge: str) -> str:
        lecturer = self.lecturer
        assert lecturer is not None
        if reached is None:
            return f"already at {edge}"
        stops = lecturer.lecture.stops
        stop = stops[reached.index]
        following = stops[reached.index + 1].title if reached.index + 1 < len(stops) else None
        self.screen.lecture = LectureStop(
            lecturer.lecture.title, reached.index, len(stops), stop.title, stop.say, reached.event, following
        )
        said = f"stop {reached.index + 1}: {stop.title} (event {reached.event})"
        return said if reached.met else f"{said}; not reached: {reached.note}"

    def set_numbers(self, on: bool) -> None:
        with self.lock:
            self.screen.numbers = bool(on)

    def set_trails(self, moves: float) -> None:
        """Draw each robot's last ``moves`` moves (0: none); a browser may send anything: a whole number
        from 0 to MAX_TRAIL, else refused."""
        if not isinstance(moves, int | float) or moves != moves or not 0 <= moves <= MAX_TRAIL:
            raise InputError(f"trails {moves!r}: choose a whole number of moves from 0 to {MAX_TRAIL}")
        with self.lock:
            self.screen.trails = int(moves)


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
