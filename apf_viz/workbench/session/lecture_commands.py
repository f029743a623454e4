"""Commands on a guided lecture: its stops, PageDown and PageUp."""

from __future__ import annotations

from apf_viz.core.formats import InputError
from apf_viz.lecture import Lecture
from apf_viz.workbench import loader
from apf_viz.workbench.lecturer import Lecturer, Reached
from apf_viz.workbench.screen_state import LectureStop
from apf_viz.workbench.session.core import shared_only
from apf_viz.workbench.session.file_commands import FileCommands
from apf_viz.workbench.session.run_commands import RunCommands
from apf_viz.workbench.view_model.story import MAX_TRAIL


class LectureCommands(RunCommands, FileCommands):
    """Commands on a guided lecture: its stops, PageDown and PageUp. Built on the run's and the files'
    commands, which a lecture drives (a Lectern: workbench/lecturer.py)."""

    # ------------------------------------------------------------------ a guided lecture
    @shared_only
    def start_lecture(self, lecture: Lecture | None) -> str:
        """Follow ``lecture`` (None: stop following one) from its first stop."""
        self.lecturer = Lecturer(self, lecture) if lecture is not None else None
        self.screen.lecture = None
        return self.next_stop() if lecture is not None else "no lecture: PageDown stops at the run's stages"

    @shared_only
    def load_lecture(self, filename: str, content: bytes) -> str:
        """A lecture file uploaded (checked whole first: a bad one leaves the run and lecture as they are)."""
        return self.start_lecture(loader.lecture_upload(filename, content))

    def next_stop(self) -> str:
        """The lecture's next stop (PageDown): run to its condition; what happened, for a notification."""
        if self.lecturer is None:
            return "no lecture loaded"
        self.pause()  # a stop's words hold at its state: Play would carry the run past it
        return self._at_stop(self.lecturer.next(), "the lecture's last stop")

    def previous_stop(self) -> str:
        if self.lecturer is None:
            return "no lecture loaded"
        self.pause()
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
            lecturer.lecture.title, reached.index, len(stops), stop.title, stop.say, reached.event,
            following, lecturer.mark, stop.class_address,
        )  # fmt: skip
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
