"""Try it yourself (workbench/classroom/own_runs.py, drawn by ui/own_runs.py): a class page's run of its
own branches from the shared run as it is, never touches it, is refused what only the shared run may do
(at the page's door, workbench/classroom/page_run.py), and is bounded."""

from __future__ import annotations

import contextlib
from types import SimpleNamespace

import numpy as np
import pytest

from apf_viz.core.formats import InputError
from apf_viz.ui.app import demo_session
from apf_viz.ui.own_runs import OwnRuns
from apf_viz.workbench.classroom import SHARED_ONLY, Classroom
from apf_viz.workbench.classroom import own_runs as classroom_own_runs
from apf_viz.workbench.classroom.own_runs import OwnPlay
from apf_viz.workbench.session.branch import branch


def _state(session):
    e = session.engine
    return e.step_index, e.state.events, np.asarray(e.positions).tolist(), list(e.state.lights)


def test_an_own_run_starts_where_the_shared_run_is_and_goes_its_own_way():
    shared = demo_session()
    for _ in range(40):
        shared.step()
    own = branch(shared)
    assert _state(own) == _state(shared) and own is not shared
    before = _state(shared)
    for _ in range(25):
        own.step()
    assert _state(shared) == before  # the shared run is untouched
    assert own.engine.step_index == 65
    own.back()
    own.set_scheduler("manual")
    assert own.scheduler_name == "manual" and shared.scheduler_name != "manual"
    for _ in range(5):
        shared.step()
    assert own.engine.step_index == 64  # and the shared run's steps do not reach it


@pytest.mark.parametrize(
    "command",
    [
        lambda s: s.load_pattern("p.json", b"{}"),
        lambda s: s.load_robots("r.json", b"{}"),
        lambda s: s.load_trace("t.jsonl", b""),
        lambda s: s.load_schedule("s.jsonl", b""),
        lambda s: s.load_lecture("l.json", b"{}"),
        lambda s: s.start_lecture(None),
        lambda s: s.save_pattern("mine"),
        lambda s: s.reveal(),
    ],
)
def test_a_page_in_its_own_run_is_refused_files_lectures_the_library_and_the_reveal(command):
    shared = demo_session()
    room = Classroom(shared)
    room.join("laptop", "class", "seat 1")
    door = room.run_of("laptop")
    room.try_alone("laptop")
    with pytest.raises(InputError, match="not in a run of your own"):
        command(door)
    room.back("laptop")  # back at the shared run, the door passes them on (the Session may refuse)
    assert door.target is shared


def test_every_shared_only_name_is_a_session_command():
    """A name misspelt in SHARED_ONLY would refuse nothing: each is a command the Session has."""
    shared = demo_session()
    assert all(callable(getattr(shared, name, None)) for name in SHARED_ONLY)


def test_the_class_permission_is_the_presenters_not_a_pages_in_its_own_run():
    shared = demo_session()
    room = Classroom(shared)
    room.join("projector", "presenter")
    room.join("laptop", "class", "seat 1")
    room.try_alone("laptop")
    with pytest.raises(InputError, match="only a presenter page opens the run"):
        room.set_class_may_drive(True, "laptop")
    assert room.may_drive("laptop") and not room.class_may_drive  # its own run, and only that


def test_an_own_run_branched_at_a_compare_compares_too():
    """Tried at a Compare stop, the copy compares with the same algorithm, its second run following the
    copy (not the shared run's second run)."""
    shared = demo_session()
    shared.compare_with("apf-opaque-grid-literal")
    for _ in range(30):
        shared.step()
    own = branch(shared)
    assert own.screen.twin is not None and own.screen.twin is not shared.screen.twin
    assert own.screen.twin.algorithm == "apf-opaque-grid-literal"
    for _ in range(10):
        own.step()
    view = own.view()
    assert view.compare is not None and view.compare.steps == view.steps == 40
    assert branch(demo_session()).screen.twin is None


def test_a_page_attached_to_its_own_run_sends_every_command_there():
    shared = demo_session()
    room = Classroom(shared)
    page = room.join(7, "class", "seat 7")
    door = room.run_of(7)
    door.step()
    assert shared.engine.step_index == 1
    room.try_alone(7)
    door.step()
    door.step()
    assert page.own is not None
    assert shared.engine.step_index == 1 and page.own.engine.step_index == 3
    assert door.engine is page.own.engine
    room.back(7)
    assert door.engine is shared.engine


class _Screen:
    """What the app's OwnRuns needs of a browser's screen, without a browser."""

    def __init__(self, page) -> None:
        self.page = page
        self.client = SimpleNamespace(client_id=page.key, atomic=contextlib.nullcontext)
        self.panels = SimpleNamespace(refresh=lambda view: None)
        self.own = None
        self.renderer = None
        self.stale = True
        self.drawn_at = 0.0

    @property
    def session(self):
        return self.page.own

    def attach_own(self, own):
        self.own = SimpleNamespace(render=lambda view: None)

    def draw_own(self, view):
        self.own.render(view)

    def detach_own(self):
        self.own = None

    def frame(self, renderer):
        pass


def test_own_runs_are_for_class_pages_bounded_in_number_and_dropped_on_the_way_back(monkeypatch):
    monkeypatch.setattr(classroom_own_runs, "MAX_OWN_RUNS", 2)
    room = Classroom(demo_session())
    for key in range(3):
        room.join(key, "class", f"seat {key}")
    room.join(9, "presenter")
    with pytest.raises(InputError, match="presenter page drives the shared run"):
        room.try_alone(9)
    assert "your own run, from event 0" in room.try_alone(0)
    room.try_alone(1)
    with pytest.raises(InputError, match="2 pages are trying runs of their own"):
        room.try_alone(2)
    assert room.back(0) == "back to the lecture" and room.page(0).own is None
    room.try_alone(2)  # room again
    assert len(room.own_pages()) == 2
    room.leave(2)  # a page that leaves drops its run, and frees its place
    assert len(room.own_pages()) == 1


def test_an_own_run_ends_a_bounded_number_of_events_past_where_it_branched(monkeypatch):
    from apf_viz.workbench.session import branch as branching

    monkeypatch.setattr(branching, "EXTRA_EVENTS", 60)
    shared = demo_session()
    for _ in range(30):
        shared.step()
    own = branch(shared)
    while own.step():
        pass
    assert own.engine.outcome == "limit"
    assert own.engine.state.events <= shared.engine.state.events + 60


def test_own_play_keeps_each_run_to_its_speed_and_all_to_their_share_of_a_frame():
    shared = demo_session()
    a, b = branch(shared), branch(shared)
    for run in (a, b):
        run.set_speed(10)
        run.toggle_play()
    pacer = OwnPlay()
    for _ in range(20):  # two seconds of frames at 10 frames a second
        assert pacer.play([a, b], frame_seconds=0.1, since=0.1)
    assert 18 <= a.engine.step_index <= 21 and 18 <= b.engine.step_index <= 21
    assert shared.engine.step_index == 0
    frozen = a.engine.step_index
    pacer.play([a], frame_seconds=0.0, since=1.0)  # no time left in the frame: nothing runs
    assert a.engine.step_index == frozen


def test_an_own_run_is_drawn_again_only_when_it_played_or_was_told_it_changed():
    """A page whose own run stands still is not drawn again each frame (24 such pages beside a playing
    projector were a view each a frame): play marks the runs it played, drawing clears the mark."""
    room = Classroom(demo_session())
    pages = [_Screen(room.join(i, "class", f"seat {i}")) for i in range(3)]
    drawn: list[int] = []
    runs = OwnRuns(room, lambda: pages, lambda: None)  # type: ignore[arg-type]
    for page in pages:
        runs.try_alone(page)  # type: ignore[arg-type]
        page.own = SimpleNamespace(render=lambda view, cid=page.client.client_id: drawn.append(cid))
    assert not any(p.stale for p in pages)  # drawn once as they branched
    pages[1].session.set_speed(10)
    pages[1].session.toggle_play()
    assert runs.play(pages, frame_seconds=0.1, since=0.1)  # type: ignore[arg-type]
    assert [p.stale for p in pages] == [False, True, False]
    runs.render(pages[1])  # type: ignore[arg-type]
    assert drawn == [1] and not pages[1].stale
    pages[1].session.pause()
    assert not runs.play(pages, frame_seconds=0.1, since=0.1) and not pages[1].stale  # type: ignore[arg-type]
