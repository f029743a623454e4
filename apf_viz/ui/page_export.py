"""A lecture or a run as one HTML page that plays with no server, no Python and no network: viser's own
client, with the scene's messages recorded frame by frame (``ViserServer.get_scene_serializer``) and
embedded (``StateSerializer.as_html``). Panels are not recorded. A lecture's page is paced like the
lecture (ui/lecture_page.py): it opens paused at stop 1, PageDown and PageUp go stop to stop, and each
stop's title and words are an HTML caption over the canvas at the projector's sizes. A run's page says
what it shows as labels above the run."""

from __future__ import annotations

import contextlib
import io
import textwrap
from dataclasses import dataclass

import viser

from apf_viz.lecture import Lecture
from apf_viz.ui.caption_room import CAPTION_ROOM
from apf_viz.ui.lecture_page import PageQuestion, PageStop, paced_page
from apf_viz.ui.network import free_port
from apf_viz.ui.scene import SceneRenderer, text_cells
from apf_viz.ui.scene.compare_pair import ComparePair
from apf_viz.workbench.question import choice_words
from apf_viz.workbench.run_config import RunConfig
from apf_viz.workbench.session import Session
from apf_viz.workbench.view_model import SessionView

STOP_SECONDS = 6.0  # a lecture's stop stays on screen this long (the page's own controls pause it)
FRAME_SECONDS = 0.15  # a kept step of a run
LINE_CHARACTERS = 90  # the words above the run wrap here
PAGE_ASPECT = 1024 / 730  # a 1024×768 projector's canvas above the player's bar: the page is framed for it


@dataclass(frozen=True)
class Exported:
    """What a page holds: its frames, the events of the run they show, and its size."""

    html: str
    frames: int
    events: int


class _Recorder:
    """A viser server no browser connects to, whose scene is recorded as it is drawn."""

    def __init__(self) -> None:
        with contextlib.redirect_stdout(io.StringIO()):  # viser's banner: no page will ever connect
            self.server = viser.ViserServer(host="127.0.0.1", port=free_port(), verbose=False)
        self.renderer = SceneRenderer(self.server, root="/shared", selection=False)
        self.pair = ComparePair(self.renderer)  # a stop that compares shows the run beside it too
        self.serializer = self.server.get_scene_serializer()
        self.frames = 0
        self.clock = 0.0  # seconds of the recording so far: where the next frame starts
        self.whole: tuple | None = None  # the box the camera frames (a lecture: every stop's)
        self.seen: list[tuple] = []  # the boxes of the frames drawn
        self._framed: tuple | None = None

    def frame(
        self, view: SessionView, words: list[str], seconds: float, config: RunConfig | None = None
    ) -> None:
        """One frame: the run as ``view`` shows it (and Compare's second run, given the run's ``config``),
        ``words`` above it (none: the page's caption says what it is), held ``seconds``."""
        with self.server.atomic():
            if config is not None:
                self.pair.render(view, config)
            else:
                self.renderer.render(view)
            if words:
                self._words(words)
            else:
                self._framed_for_caption()
        self.frames += 1
        self.serializer.insert_sleep(seconds)
        self.clock += seconds

    def _framed_for_caption(self) -> None:
        """The camera the page opens with: every stop's runs (:attr:`whole`, once known, else the run),
        above the room the caption takes at the bottom. The page's camera stays where it opened (the
        player does not move it), so it is framed on the whole lecture."""
        bounds = self.whole if self.whole is not None else self.renderer.bounds
        self.seen.append(self.renderer.bounds)
        if bounds != self._framed:
            self._framed = bounds
            self.renderer.frame_initial_camera(self.server.initial_camera, bounds, PAGE_ASPECT, CAPTION_ROOM)

    def _words(self, words: list[str]) -> None:
        lines = [line for text in words for line in (textwrap.wrap(text, LINE_CHARACTERS) or [""])]
        x0, y0, x1, y1 = self.renderer.bounds
        h = text_cells(self.renderer.visible_height()) * 1.45  # a line and the space under it
        top = y1 + 1.5 + h * len(lines)
        placed = [(line, (x0 - 0.5, top - h * i, 0.1)) for i, line in enumerate(lines)]
        self.renderer.words("/words", placed)
        bounds = (x0, y0, max(x1, x0 + 0.55 * h / 1.45 * LINE_CHARACTERS), top + h)
        if bounds != self._framed:  # the camera the page opens with: the run and its words
            self._framed = bounds
            self.renderer.frame_initial_camera(self.server.initial_camera, bounds)

    def html(self) -> str:
        return self.serializer.as_html()

    def close(self) -> None:
        with contextlib.redirect_stdout(io.StringIO()):
            self.server.stop()


def export_lecture(session: Session, lecture: Lecture) -> Exported:
    """Every stop as the browser shows it after PageDown, held :data:`STOP_SECONDS` when played: one page
    that opens paused at stop 1 and goes stop to stop with PageDown and PageUp, each stop's title and
    words in an HTML caption over the canvas. Recorded twice: the first pass finds the box that holds
    every stop's runs, which the page's one camera frames."""
    scratch = _Recorder()
    try:
        _record_stops(session, lecture, scratch)
        xs0, ys0, xs1, ys1 = zip(*scratch.seen, strict=True)
    finally:
        scratch.close()
    recorder = _Recorder()
    recorder.whole = (min(xs0), min(ys0), max(xs1), max(ys1))
    try:
        stops = _record_stops(session, lecture, recorder)
        page = paced_page(recorder.html(), lecture.title, stops, STOP_SECONDS)
        return Exported(page, recorder.frames, session.engine.state.events)
    finally:
        recorder.close()


def _record_stops(session: Session, lecture: Lecture, recorder: _Recorder) -> list[PageStop]:
    session.start_lecture(lecture)
    stops: list[PageStop] = []
    for i in range(len(lecture.stops)):
        if i:
            session.next_stop()
        view = session.view()
        assert view.lecture is not None
        where, title, say = view.lecture
        status = f"{view.stage_line} · event {view.event}"
        at = recorder.clock
        recorder.frame(view, [], STOP_SECONDS, session.config)
        stops.append(PageStop(at, where, title, say, status, _asked(session, recorder)))
    return stops


def _asked(session: Session, recorder: _Recorder) -> PageQuestion | None:
    """A stop's question on the page: its choices, the run's answer, and a frame of the run where it
    shows the answer (recorded after the stop's own), which the page's reveal goes to."""
    poll = session.screen.poll
    if poll is None:
        return None
    here = session.engine.step_index
    session.seek(poll.answer.step)
    reveal_at = recorder.clock
    there = session.view()
    recorder.frame(there, [], STOP_SECONDS, session.config)
    session.seek(here)  # where the stop left the run: the next stop goes on from there
    choices = (
        tuple((c, choice_words(poll.kind, c)) for c in poll.choices) if poll.choices is not None else None
    )
    return PageQuestion(
        poll.question,
        poll.kind,
        choices,
        tuple(sorted(poll.answer.right)),
        f"{poll.answer.words()} (event {poll.answer.event})",
        reveal_at,
        f"{there.stage_line} · event {there.event}",
    )


def export_run(session: Session, title: str) -> Exported:
    """The run from its start to where it is now (or, when it is at its start, to its end): every step
    that moves a robot or changes a light is a frame; Looks and Computes that change nothing on screen
    are merged into the frame they lead to, and the page says so."""
    recorder = _Recorder()
    try:
        end = session.engine.step_index
        if end == 0:
            while session.step():
                pass
            end = session.engine.step_index
        session.seek(0)
        kept, last = 0, _picture(session.view())
        recorder.frame(session.view(), [title, "the start"], 1.0)
        for step in range(1, end + 1):
            session.seek(step)
            view = session.view()
            if _picture(view) != last or step == end:
                last = _picture(view)
                kept += 1
                state = view.outcome.upper() if view.outcome else "running"
                recorder.frame(
                    view,
                    [title, f"event {view.event} · {state} · {kept} frames of {step} steps"],
                    FRAME_SECONDS,
                )
        recorder.serializer.insert_sleep(STOP_SECONDS)
        note = (
            f"thinned: {kept} frames for {end} steps ({session.engine.state.events} events); every move kept"
        )
        recorder.frame(session.view(), [title, note], STOP_SECONDS)
        return Exported(recorder.html(), recorder.frames, session.engine.state.events)
    finally:
        recorder.close()


def _picture(view: SessionView) -> tuple:
    """What a frame of the run shows: where each robot is and its light."""
    return tuple((r.position, r.light) for r in view.robots)
