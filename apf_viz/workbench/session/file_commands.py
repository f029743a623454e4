"""Commands on files: loading a pattern, robots, a scenario, a trace or a schedule; the files to save."""

from __future__ import annotations

import re

from apf_viz.core.files import read_bytes
from apf_viz.core.formats import (
    MAX_INPUT_BYTES,
    MAX_TRACE_BYTES,
    InputError,
    pattern_json,
    robots_json,
    trace_text,
)
from apf_viz.core.grid import as_point
from apf_viz.core.run import trace_header
from apf_viz.core.schedule import Schedule, ScheduleError, follow, schedule_of_steps, schedule_text
from apf_viz.demos import pattern_of_size, scenarios
from apf_viz.workbench import loader
from apf_viz.workbench.run_config import RunConfig
from apf_viz.workbench.session.core import SCHEDULER_LABELS, SessionCore


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


class FileCommands(SessionCore):
    """Commands on files: loading a pattern, robots, a scenario, a trace or a schedule; the files to save."""

    # ------------------------------------------------------------------ files
    def load_pattern(self, filename: str, content: bytes) -> str | None:
        """A pattern file; if its size fits the robots the run restarts with it, otherwise it becomes the
        pattern being drawn (Edit pattern), so nothing is lost; then what to do is returned."""
        read = loader.pattern_upload(filename, content)
        points = tuple(as_point(p) for p in read.points)
        with self.lock:
            self.name_pattern(points, read.name or "")
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
            self.load_trace(path.name, read_bytes(path, MAX_TRACE_BYTES), MAX_TRACE_BYTES)  # our own file
            self.scenario_note = scenario.shows
            return scenario.shows
        pattern = loader.pattern_upload(files["pattern"].name, read_bytes(files["pattern"], MAX_INPUT_BYTES))
        robots = loader.robots_upload(files["robots"].name, read_bytes(files["robots"], MAX_INPUT_BYTES))
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
            written: dict[int, str] = {}  # the step a line's note belongs to: the last step it made
            try:
                for n in follow(engine, schedule, filename):
                    if n in schedule.notes:
                        written[engine.step_index] = schedule.notes[n]
            except ScheduleError as e:
                notes.append(f"{e}; the run follows the schedule up to there")
            self._drafts_follow(config)
            found = {"found": schedule.found.words()} if schedule.found is not None else None
            self.run.adopt(config, engine, engine.state.events, found, what=f"the schedule {filename}")
            self.run.step_notes = written
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
        """The robots the page shows as a robots file: the drawn ones in Edit robots, the run's start
        elsewhere."""
        with self.lock:
            if self.mode == "edit-robots":
                return robots_json(self.editor.robots, self.editor.y_up)
            return robots_json(self.config.robots, self.config.y_up)

    def pattern_file(self) -> str:
        """The pattern the page shows (the drawn one in either Edit mode, the run's in Run), named as it
        was saved or loaded, else by its size."""
        with self.lock:
            cells = list(self.editor.pattern if self.mode != "run" else self.config.pattern)
            return pattern_json(cells, self.pattern_name(cells) or f"pattern of {len(cells)} cells")

    def pattern_file_name(self) -> str:
        """The file a download of :meth:`pattern_file` is saved as: its name's (``APF.pattern.json``), else
        ``pattern.json``."""
        with self.lock:
            cells = list(self.editor.pattern if self.mode != "run" else self.config.pattern)
            name = self.pattern_name(cells)
        stem = re.sub(r"[^A-Za-z0-9_.-]+", "-", name or "").strip("-.")[:80]
        return f"{stem}.pattern.json" if stem else "pattern.json"

    def trace_file(self) -> str:
        """The run as a trace file, at any moment, with its verdict: while a trace or branch is followed,
        its whole line (what its header said kept, and the event the page stands at); else the run so
        far, up to the step shown, with its outcome so far."""
        with self.lock:
            e, run = self.engine, self.run
            if run.following:
                upto = e.history.length
                options: dict[str, object] = {**run.line_verdict(), **run.trace_options}
                options["shown_at_event"] = e.state.events
            else:
                upto = e.step_index
                options = {"verdict": e.state.outcome or "running", "events": e.state.events}
            header = trace_header(e, self.scheduler_name, self.seed, options)
            return trace_text(header, e.history.events(upto))
