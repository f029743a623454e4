"""One shared run behind the visualiser: step, back, seek, play speed, manual picks, edits, files.

No viser here: the app turns clicks into calls on a :class:`Session` and renders :meth:`Session.view`.
Every call is serialised by one lock, so all connected browsers drive the same run safely.
"""

from __future__ import annotations

import threading
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from itertools import repeat
from typing import Literal, NamedTuple

import numpy as np

from apf_viz.algorithms import Factory, get_algorithm
from apf_viz.algorithms.apf_opaque_grid import embedded_targets
from apf_viz.core.engine import NEXT_EVENT, Engine, Phase
from apf_viz.core.formats import (
    InputError,
    PatternFile,
    RobotsFile,
    parse_pattern,
    parse_robots,
    parse_trace,
    pattern_json,
    robots_json,
    trace_text,
)
from apf_viz.core.frames import move_to_global, random_y_up, to_local
from apf_viz.core.grid import COORD_LIMIT, Point, short_int
from apf_viz.core.pattern_match import matches_pattern
from apf_viz.core.run import engine_for_trace, replay, trace_header
from apf_viz.core.schedulers import make_scheduler, step_rng
from apf_viz.core.symmetry import describe_axis, unsolvable_axis
from apf_viz.ui.move_series import MoveSeries

Mode = Literal["run", "edit-pattern", "edit-robots"]
SCHEDULER_LABELS = {
    "FSYNC": "fsync",
    "SSYNC": "ssync",
    "ASYNC": "async",
    "stale-first": "stale-first",
    "round-robin": "round-robin",
    "Manual": "manual",
}
MAX_UPLOAD_BYTES = 2_000_000
MAX_SPEED = 500.0  # steps per second: the Speed slider's top


_PHASE_NAMES = ("idle", "looked", "computed")  # indexed by Phase
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
class SessionView:
    """Everything the scene and panels show, computed in one place from the engine's state."""

    robots: tuple[RobotView, ...]
    targets: tuple[Point, ...]
    selected: int | None
    rays: tuple[tuple[Point, Point], ...]
    ghosts: tuple[Point, ...]
    line_K: float | None  # y of K, when two terminal1/decider robots define it
    leader_frame: tuple[Point, int] | None  # global origin of the leader's frame and its +y sign
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


class Session:
    """The run everyone sees. Build it from a start and a pattern; reset rebuilds the engine from them."""

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
        self.lock = threading.RLock()
        # The only algorithms a name from a trace may choose: built-ins and what the command line loaded.
        self.plugins: Mapping[str, Factory] = dict(plugins or {})
        self.algorithm_name = algorithm
        self.scheduler_name = scheduler
        self.seed = seed
        self.light_semantics = light_semantics
        self.max_events = max_events
        self.mode: Mode = "run"
        self.selected: int | None = None
        self.playing = False
        self.speed = 10.0  # steps per second
        self.messages: list[str] = []  # notifications for the UI to show, drained by the app
        self._start(list(robots), list(pattern), y_up)

    # ------------------------------------------------------------------ building runs
    def _start(self, robots: list[Point], pattern: list[Point], y_up: Sequence[bool] | None) -> None:
        if len(robots) != len(pattern):
            raise InputError(f"the pattern has {len(pattern)} points but there are {len(robots)} robots")
        self.robots = [tuple(p) for p in robots]
        self.pattern = [tuple(p) for p in pattern]
        self.y_up = list(y_up) if y_up is not None else random_y_up(len(robots), self.seed)
        self.engine = Engine(
            self.robots,
            self.pattern,
            get_algorithm(self.algorithm_name, self.plugins),
            y_up=self.y_up,
            light_semantics=self.light_semantics,  # type: ignore[arg-type]
            max_events=self.max_events,
        )
        self.draft_pattern = list(self.pattern)
        self.draft_robots = list(self.robots)
        self.draft_y_up = list(self.y_up)
        self.selected = None
        self._series = MoveSeries(self.robots)

    def reset(self) -> None:
        """Back to the start of the current run (same start, pattern, flips, algorithm)."""
        with self.lock:
            self.playing = False
            self._start(self.robots, self.pattern, self.y_up)

    # ------------------------------------------------------------------ stepping
    def step(self) -> bool:
        """One step chosen by the scheduler (in Manual: the selected robot). False if nothing ran."""
        with self.lock:
            if self.engine.finished or self.mode != "run":
                return False
            if self.scheduler_name == "manual":
                if self.selected is None:
                    self.messages.append("Manual: click a robot to run its next phase")
                    return False
                self.engine.step([self.selected])
                return True
            record = make_scheduler(self.scheduler_name).choose(
                self.engine, step_rng(self.seed, self.engine.step_index)
            )
            self.engine.step(record.robots, round=record.round)
            return True

    def back(self) -> None:
        with self.lock:
            self.engine.back(1)

    def seek(self, step: int) -> None:
        with self.lock:
            self.engine.seek(max(0, min(step, self.engine.history.length)))

    def seek_from_browser(self, step: float) -> None:
        """The Timeline slider: stop playing and go to that step (any number is clamped; NaN refused)."""
        if not isinstance(step, int | float) or step != step:
            raise InputError(f"timeline position {step!r} is not a number")
        with self.lock:
            self.playing = False
            self.seek(int(min(max(step, 0), self.engine.history.length)))

    def set_scheduler(self, label_or_name: str) -> None:
        with self.lock:
            self.scheduler_name = SCHEDULER_LABELS.get(label_or_name, label_or_name)
            make_scheduler(self.scheduler_name)  # validates the name

    def set_seed(self, seed: float) -> None:
        """A seed typed in the browser: a whole number in 0 .. 2^63 − 1, anything else is refused."""
        if not (isinstance(seed, int | float) and float(seed).is_integer() and 0 <= seed < 2**63):
            raise InputError(f"seed {seed!r}: a seed is a whole number from 0 to 2^63 − 1")
        with self.lock:
            self.seed = int(seed)

    def set_speed(self, speed: float) -> None:
        """Steps per second while playing, clamped to 1 .. MAX_SPEED (a browser may send anything)."""
        if not isinstance(speed, int | float) or speed != speed:  # NaN
            raise InputError(f"speed {speed!r} is not a number")
        with self.lock:
            self.speed = float(min(max(speed, 1.0), MAX_SPEED))

    # ------------------------------------------------------------------ clicks
    def robot_at(self, cell: Point) -> int | None:
        hits = np.flatnonzero((self.engine.positions == np.array(cell)).all(axis=1))
        return int(hits[0]) if hits.size else None

    def click(self, cell: Point) -> str:
        """A click on a grid cell, interpreted by the current mode. Returns what happened."""
        with self.lock:
            if abs(cell[0]) > COORD_LIMIT or abs(cell[1]) > COORD_LIMIT:
                message = (
                    f"({short_int(cell[0])}, {short_int(cell[1])}) is outside the grid this tool supports "
                    f"(|x|, |y| ≤ {COORD_LIMIT:,})"
                )
                self.messages.append(message)
                return message
            if self.mode == "edit-pattern":
                return self._toggle(self.draft_pattern, cell, "target")
            if self.mode == "edit-robots":
                return self._cycle_robot(cell)
            r = self.robot_at(cell)
            if r is None:
                self.selected = None
                return "nothing here"
            self.selected = r
            if self.scheduler_name == "manual" and not self.engine.finished:
                phase = self.engine.next_event(r)
                self.engine.step([r])
                return f"robot {r}: {phase}"
            return f"selected robot {r}"

    def _toggle(self, points: list[Point], cell: Point, what: str) -> str:
        if cell in points:
            points.remove(cell)
            return f"removed {what} {cell}"
        points.append(cell)
        return f"added {what} {cell}"

    def _cycle_robot(self, cell: Point) -> str:
        """Empty → robot (y up) → robot (y flipped) → empty."""
        if cell not in self.draft_robots:
            self.draft_robots.append(cell)
            self.draft_y_up.append(True)
            return f"added robot {cell}"
        i = self.draft_robots.index(cell)
        if self.draft_y_up[i]:
            self.draft_y_up[i] = False
            return f"robot {cell}: y-axis flipped"
        del self.draft_robots[i]
        del self.draft_y_up[i]
        return f"removed robot {cell}"

    # ------------------------------------------------------------------ editing
    def set_mode(self, mode: Mode) -> str | None:
        """Switch modes. Leaving an edit mode validates the drafts and restarts the run; on a problem the
        mode stays, the drafts are kept, and the problem is returned (and queued as a message)."""
        with self.lock:
            if mode == self.mode:
                return None
            if self.mode != "run" and mode == "run":
                problem = self.validate_drafts()
                if problem:
                    self.messages.append(problem)
                    return problem
                self.playing = False
                self._start(self.draft_robots, self.draft_pattern, self.draft_y_up)
            elif mode != "run":
                self.playing = False
            self.mode = mode
            return None

    def validate_drafts(self) -> str | None:
        if not self.draft_robots:
            return "place at least one robot"
        if len(self.draft_pattern) != len(self.draft_robots):
            return (
                f"the pattern has {len(self.draft_pattern)} points but there are "
                f"{len(self.draft_robots)} robots"
            )
        axis = unsolvable_axis(self.draft_robots)
        if axis is not None and not matches_pattern(self.draft_robots, self.draft_pattern):
            return (
                f"unsolvable start: the robots are mirror-symmetric about {describe_axis(axis)}, "
                "a horizontal line through no robot (Theorem 1); move or add a robot to break the symmetry"
            )
        return None

    def clear_pattern(self) -> None:
        with self.lock:
            self.draft_pattern = []

    # ------------------------------------------------------------------ files
    def load_pattern(self, filename: str, content: bytes) -> None:
        """A pattern file; if its size fits the robots the run restarts with it, otherwise it becomes the
        pattern being drawn (Edit pattern), so nothing is lost."""
        parsed = self._parse(filename, content, parse_pattern)
        assert isinstance(parsed, PatternFile)
        points = [tuple(p) for p in parsed.points]
        with self.lock:
            if len(points) == len(self.robots):
                self.playing = False
                self._start(self.robots, points, self.y_up)
                self.mode = "run"
            else:
                self.draft_pattern = points
                self.mode = "edit-pattern"
                self.messages.append(
                    f"{filename}: {len(points)} points for {len(self.robots)} robots: "
                    "edit the pattern or the robots, then switch back to Run"
                )

    def load_robots(self, filename: str, content: bytes) -> None:
        parsed = self._parse(filename, content, parse_robots)
        assert isinstance(parsed, RobotsFile)
        points = [tuple(p) for p in parsed.robots]
        y_up = parsed.flips(self.seed)  # the same rule as every other way in (RobotsFile.flips)
        with self.lock:
            self.draft_robots, self.draft_y_up = points, list(y_up)
            self.draft_pattern = list(self.pattern)
            problem = self.validate_drafts()
            if problem is None:
                self.playing = False
                self._start(points, self.pattern, y_up)
                self.mode = "run"
            else:
                self.mode = "edit-robots"
                self.messages.append(f"{filename}: {problem}")

    def load_trace(self, filename: str, content: bytes) -> None:
        """Replay a trace: checked event by event; the current run is untouched if it does not replay."""
        text = self._decode(filename, content)
        header, events = parse_trace(text, filename)
        try:  # a file names built-in algorithms (or the command line's plug-ins) only: it never loads code
            algorithm = get_algorithm(header.algorithm, self.plugins)
        except ValueError as e:
            raise InputError(f"{filename}: {e}") from None
        engine = engine_for_trace(header, algorithm, max(self.max_events, len(events) + 1))
        replay(engine, events, filename)
        with self.lock:
            self.playing = False
            self.algorithm_name = header.algorithm
            self.light_semantics = header.light_semantics
            self.robots = list(engine.start)
            self.pattern = list(engine.pattern)
            self.y_up = list(engine.y_up)
            self.draft_robots, self.draft_pattern = list(self.robots), list(self.pattern)
            self.draft_y_up = list(self.y_up)
            engine.seek(0)
            self.engine = engine
            self._series = MoveSeries(engine.start)
            self.mode = "run"
            self.selected = None

    def _decode(self, filename: str, content: bytes) -> str:
        if len(content) > MAX_UPLOAD_BYTES:
            size = len(content)
            raise InputError(f"{filename}: file is too large ({size} bytes, limit {MAX_UPLOAD_BYTES})")
        try:
            return content.decode("utf-8")
        except UnicodeDecodeError:
            raise InputError(f"{filename}: not UTF-8 text") from None

    def _parse(self, filename: str, content: bytes, parser):
        return parser(self._decode(filename, content), filename)

    def robots_file(self) -> str:
        with self.lock:
            return robots_json(self.draft_robots if self.mode == "edit-robots" else self.robots, self.y_up)

    def pattern_file(self) -> str:
        with self.lock:
            return pattern_json(self.draft_pattern if self.mode == "edit-pattern" else self.pattern)

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
        phases = st.phase.tolist()
        pending: list[Point | None] = [None] * e.k
        for r in np.flatnonzero(st.phase == _COMPUTED).tolist():
            if st.pending[r].move is not None:
                dx, dy = move_to_global(st.pending[r].move, self.y_up[r]).delta
                pending[r] = (pts[r][0] + dx, pts[r][1] + dy)
        # tuple.__new__ mapped in C: a thousand robots a frame, and a NamedTuple's __new__ is Python.
        robots = list(
            map(
                tuple.__new__,
                repeat(RobotView),
                zip(
                    pts,
                    st.lights,
                    [_PHASE_NAMES[p] for p in phases],
                    self.y_up,
                    pending,
                    [NEXT_EVENT[p] for p in phases],
                    strict=True,
                ),
            )
        )
        if self.mode == "edit-robots":  # the robots being placed, not the run's
            first = e.algorithm.lights[0]
            robots = [
                RobotView(p, first, "idle", up, None, "look")
                for p, up in zip(self.draft_robots, self.draft_y_up, strict=True)
            ]
        sel = self.selected if self.selected is not None and self.selected < e.k else None
        if self.mode != "run":
            sel = None
        rays: list[tuple[Point, Point]] = []
        ghosts: list[Point] = []
        if sel is not None:
            rays = [(pts[sel], pts[j]) for j in e.visible(sel).tolist()]
            snap = st.snapshot[sel]
            if snap is not None:
                x, y = pts[sel]
                ghosts = [(x + s.dx, y + to_local((0, s.dy), self.y_up[sel])[1]) for s in snap.robots]
        frame = self._leader_frame(pts, st.lights)
        return SessionView(
            robots=tuple(robots),
            targets=self._targets(frame),
            selected=sel,
            rays=tuple(rays),
            ghosts=tuple(ghosts),
            line_K=self._line_K(pts, st.lights),
            leader_frame=frame,
            outcome=st.outcome,
            caption=self._caption(sel),
            event=st.events,
            steps=st.steps,
            history_length=e.history.length,
            moves=st.moves,
            cycles=st.cycles,
            stage=self._stage(st.lights),
            lights_in_use=tuple(sorted(set(st.lights), key=e.algorithm.lights.index)),
            moves_per_kD=st.moves / (e.k * self._D()),
            mode=self.mode,
            draft_count=len(self.draft_pattern) if self.mode != "edit-robots" else len(self.draft_robots),
            robot_count=len(self.draft_robots) if self.mode == "edit-robots" else e.k,
            axis=(float(a) if (a := unsolvable_axis(self.draft_robots)) is not None else None)
            if self.mode == "edit-robots"
            else None,
            move_series=self._series.at(e.history, e.step_index),
        )

    def _D(self) -> int:
        """D = max(m, n, M, N, k) of the paper: the enclosing rectangles of start and pattern, and k."""

        def extent(points: list[Point]) -> tuple[int, int]:
            xs, ys = [p[0] for p in points], [p[1] for p in points]
            return max(xs) - min(xs) + 1, max(ys) - min(ys) + 1

        return max(*extent(self.robots), *extent(self.pattern), len(self.robots))

    def _caption(self, sel: int | None) -> str:
        if sel is None:
            return "Click a robot to see what it sees and why it acts."
        e = self.engine
        st = e.state
        last = next(
            (
                ev
                for s in reversed(e.history.steps[: e.step_index])
                for ev in s.events
                if ev.robot == sel and ev.phase == "compute"
            ),
            None,
        )
        phase = ("idle", "looked", "computed")[st.phase[sel]]
        lines = [
            f"**Robot {sel}** — light `{st.lights[sel]}`, {phase}; next: {e.next_event(sel)}; "
            f"y-axis {'up' if self.y_up[sel] else 'flipped'}",
        ]
        if last is not None:
            lines.append(f"Last decision: {last.rule or '(no rule given)'}")
        if st.phase[sel] != Phase.IDLE and st.look_version[sel] != st.version:
            lines.append("Its snapshot is stale: the configuration changed since its Look (ghosts show it).")
        return "\n\n".join(lines)

    @staticmethod
    def _line_K(pts: list[Point], lights: list[str]) -> float | None:
        """K: the midline of two terminal1 or two decider robots on one vertical line."""
        for light in ("decider", "terminal1"):
            by_x: dict[int, list[int]] = {}
            for (x, y), lt in zip(pts, lights, strict=True):
                if lt == light:
                    by_x.setdefault(x, []).append(y)
            for ys in by_x.values():
                if len(ys) == 2:
                    return (ys[0] + ys[1]) / 2
        return None

    @staticmethod
    def _leader_frame(pts: list[Point], lights: list[str]) -> tuple[Point, int] | None:
        """The leader's frame in global terms: origin (leader + (0, s)), and s = the side of the others."""
        if "leader" not in lights:
            return None
        lx, ly = pts[lights.index("leader")]
        others = [y for (x, y), lt in zip(pts, lights, strict=True) if lt != "leader" and y != ly]
        s = 1 if not others or others[0] > ly else -1
        return (lx, ly + s), s

    def _targets(self, frame: tuple[Point, int] | None) -> tuple[Point, ...]:
        """Where the pattern will form: in the leader's frame once there is one, else beside the start."""
        pattern = self.draft_pattern if self.mode == "edit-pattern" else self.pattern
        if self.mode == "edit-pattern":
            return tuple(pattern)
        if not pattern:
            return ()
        targets = embedded_targets(tuple(pattern))
        if frame is not None:
            (ox, oy), s = frame
            return tuple((ox + x, oy + s * y) for x, y in targets)
        x0 = max(p[0] for p in self.robots) + 3
        y0 = min(p[1] for p in self.robots) - 1
        return tuple((x0 + x, y0 + y) for x, y in targets)

    @staticmethod
    def _stage(lights: list[str]) -> str:
        if "leader" not in lights and "done" not in lights:
            return "leader election"
        if "done" in lights:
            return "targets"
        return "line"
