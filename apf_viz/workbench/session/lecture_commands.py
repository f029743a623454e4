"""Commands on a guided lecture: its stops, PageDown and PageUp."""

from __future__ import annotations

from apf_viz.core.formats import InputError
from apf_viz.lecture import Lecture
from apf_viz.workbench import loader
from apf_viz.workbench.lecturer import Lecturer, Reached
from apf_viz.workbench.poll import Poll
from apf_viz.workbench.question import cell_choice
from apf_viz.workbench.screen_state import LectureStop
from apf_viz.workbench.session.file_commands import FileCommands
from apf_viz.workbench.session.run_commands import RunCommands
from apf_viz.workbench.view_model.story import MAX_TRAIL


class LectureCommands(RunCommands, FileCommands):
    """Commands on a guided lecture: its stops, PageDown and PageUp. Built on the run's and the files'
    commands, which a lecture drives (a Lectern: workbench/lecturer.py)."""

    # ------------------------------------------------------------------ a guided lecture
    def start_lecture(self, lecture: Lecture | None) -> str:
        """Follow ``lecture`` (None: stop following one) from its first stop."""
        self.lecturer = Lecturer(self, lecture) if lecture is not None else None
        self.screen.lecture = self.screen.poll = None
        return self.next_stop() if lecture is not None else "no lecture: PageDown stops at the run's stages"

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
        """The lecture's previous stop (PageUp), replayed; what happened, for a notification."""
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
        self.screen.poll = self._poll_at(lecturer.lecture.title, reached)
        said = f"stop {reached.index + 1}: {stop.title} (event {reached.event})"
        return said if reached.met else f"{said}; not reached: {reached.note}"

    def _poll_at(self, lecture: str, reached: Reached) -> Poll | None:
        """The stop's question: the room's answers of an earlier visit kept (PageUp, then PageDown back
        to it: nobody answers twice), unless the run's answer there changed."""
        answer = reached.answer
        if answer is None:
            return None
        kept = self.polls.get((lecture, reached.index))
        if kept is not None and (kept.answer.right, kept.answer.step) == (answer.right, answer.step):
            return kept
        poll = Poll(answer, self.engine.k, tuple(self.engine.algorithm.lights))
        self.polls[(lecture, reached.index)] = poll
        return poll

    # ------------------------------------------------------------------ a stop's question
    def answer_question(self, who: str | None, choice: str) -> str:
        """Page ``who`` answers the stop's question (again: its answer changes); for that page only."""
        with self.lock:
            if self.screen.poll is None:
                raise InputError("no question is asked now")
            return self.screen.poll.give(who, choice)

    def answer_by_click(self, who: str | None, cell: tuple[int, int]) -> str | None:
        """A class page clicked ``cell`` while a question that a click answers is asked: the robot on it
        (which robot moves next) or the cell itself (where it moves); None if the click answers nothing."""
        with self.lock:
            poll = self.screen.poll
            if poll is None or poll.revealed or poll.kind not in ("robot", "cell"):
                return None
            if poll.kind == "cell":
                return poll.give(who, cell_choice(*cell))
            on = [i for i, p in enumerate(self.engine.current_points()) if tuple(p) == tuple(cell)]
            return poll.give(who, str(on[0])) if on else None

    def seat_the_room(self, seats: frozenset[str]) -> None:
        """The class pages' seats connected now: the question's count says how many of them answered."""
        with self.lock:
            self.screen.seats_here = seats

    def toggle_spread(self) -> str:
        """Show or hide, on the presenter's caption, how the room answered (a bar per choice)."""
        with self.lock:
            poll = self.screen.poll
            if poll is None:
                return "no question is asked now"
            poll.spread_shown = not poll.spread_shown
            return f"the room's answers {'shown' if poll.spread_shown else 'hidden'}: {poll.count} answered"

    def reveal(self) -> str:
        """The answer: the run plays from the stop to where it shows it (pressed again while it plays:
        there at once), and the answer is marked."""
        with self.lock:
            poll = self.screen.poll
            if poll is None:
                return "no question is asked now"
            poll.revealed = True
            stop = self.screen.lecture
            step = poll.answer.step
            e = self.engine
            on_history = stop is not None and stop.mark is not None and stop.mark.on_history(e)
            if on_history and e.history.length >= step:
                if e.step_index < step and not self.run.playing:
                    self.run.play_to(step)
                else:
                    self.run.seek(step)
            if poll.kind != "outcome":
                self.presenter.selected = poll.answer.question.robot
                if poll.kind == "robot":
                    self.presenter.selected = int(min(poll.answer.right, key=int))
            right = poll.right_count
            return f"the run's answer: {poll.answer.words()}; {right} of {poll.count} answered it"

    def set_numbers(self, on: bool) -> None:
        """Robot numbers on the canvas, on or off."""
        with self.lock:
            self.screen.numbers = bool(on)

    def set_trails(self, moves: float) -> None:
        """Draw each robot's last ``moves`` moves (0: none); a browser may send anything: a whole number
        from 0 to MAX_TRAIL, else refused."""
        if not isinstance(moves, int | float) or moves != moves or not 0 <= moves <= MAX_TRAIL:
            raise InputError(f"trails {moves!r}: choose a whole number of moves from 0 to {MAX_TRAIL}")
        with self.lock:
            self.screen.trails = int(moves)
