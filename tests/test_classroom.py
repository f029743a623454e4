"""The classroom (workbench/classroom), with no viser server: a class of 60 pages goes through a lecture
against the Classroom alone (which imports no viser: tests/test_house.py) — join with their seats,
answer a stop's question, reload, be handed the run and have it taken back, try runs of their own, and
leave — and the play clock shares the frames."""

from __future__ import annotations

import pytest

from apf_viz.core.formats import InputError
from apf_viz.lecture import find_lecture
from apf_viz.workbench.classroom import FPS, MAX_OWN_RUNS, Classroom
from apf_viz.workbench.seats import Seats
from apf_viz.workbench.session.demo import demo_session

CLASS = 60
HEART = "algorithm-in-12-stops"


def _class(room: Classroom, n: int = CLASS) -> dict[str, str]:
    """``n`` class pages, each from an address of its own with the seat the server issued it; their
    keys (connections) and seats."""
    pages = {}
    for i in range(n):
        seat = room.seats.key(room.seats.issue(f"10.0.{i // 250}.{i % 250}"))
        assert seat is not None
        room.join(f"page {i}", "class", seat)
        pages[f"page {i}"] = seat
    return pages


def _to_question(room: Classroom) -> int:
    """PageDown from the lecture's start to its first stop that asks the room; the stop's index."""
    s = room.shared
    s.start_lecture(find_lecture(HEART))
    while s.screen.poll is None:
        said = s.next_stop()
        assert "already at" not in said, "the lecture asks no question"
    assert s.screen.lecture is not None
    return s.screen.lecture.index


def test_a_class_of_sixty_goes_through_a_lecture_against_the_classroom_alone():
    s = demo_session()
    room = Classroom(s, seats=Seats(per_address=1))
    room.join("projector", "presenter")
    pages = _class(room)
    assert s.screen.seats_here == frozenset(pages.values())  # the question's "of 60" counts them
    assert [room.laptop(k) for k in pages] == list(range(1, CLASS + 1))
    assert not any(room.may_drive(k) for k in pages) and room.may_drive("projector")

    stop = _to_question(room)
    poll = s.screen.poll
    assert poll is not None and poll.choices is not None
    for i, key in enumerate(pages):  # every page answers; a third change their minds once
        room.answer(key, poll.choices[i % len(poll.choices)])
        if i % 3 == 0:
            room.answer(key, poll.choices[(i + 1) % len(poll.choices)])
    assert poll.count == CLASS and poll.view(s.screen.seats_here).present == CLASS
    chosen = {seat: poll.given(seat) for seat in pages.values()}

    # Ten pages reload: a new connection each, the same seat (its answer and laptop number kept).
    for i in range(10):
        old = f"page {i}"
        room.leave(old)
        seat = pages.pop(old)
        pages[f"page {i} again"] = seat
        room.join(f"page {i} again", "class", seat)
        assert room.laptop(f"page {i} again") == i + 1
    assert poll.count == CLASS and {seat: poll.given(seat) for seat in pages.values()} == chosen
    assert len(room.listing()) == CLASS and all(p.answered for p in room.listing())

    # The presenter hands the run to laptop 7 and takes it back; a class page cannot hand it on.
    seventh = next(k for k in pages if room.laptop(k) == 7)
    with pytest.raises(InputError, match="only a presenter page"):
        room.hand(8, seventh)
    room.hand(7, "projector")
    assert room.may_drive(seventh) and sum(room.may_drive(k) for k in pages) == 1
    room.hand(None, "projector")
    assert not any(room.may_drive(k) for k in pages)

    # Thirty pages try a run of their own: the bound lets MAX_OWN_RUNS in; each steps its own alone.
    event = s.engine.state.events
    refused = 0
    for key in list(pages)[:30]:
        try:
            room.try_alone(key)
        except InputError:
            refused += 1
    own = room.own_pages()
    assert len(own) == MAX_OWN_RUNS and refused == 30 - MAX_OWN_RUNS
    for page in own[:5]:
        door = room.run_of(page.key)
        door.step()
        assert door.engine.state.events > event
    assert s.engine.state.events == event  # the projector's run is untouched
    with pytest.raises(InputError, match="not in a run of your own"):
        room.run_of(own[0].key).reveal()  # the reveal is the lecture's, not an own run's
    for page in own:
        room.back(page.key)
    assert room.own_pages() == []

    # The presenter reveals; twenty pages leave; those who answered still count among those asked.
    said = s.reveal()
    right = sum(1 for seat in pages.values() if chosen[seat] in poll.answer.right)
    assert poll.revealed and f"{right} of {CLASS} answered it" in said
    for key in list(pages)[:20]:
        room.leave(key)
    assert len(s.screen.seats_here) == CLASS - 20 and poll.view(s.screen.seats_here).present == CLASS
    with pytest.raises(InputError, match="answer is out"):
        room.answer(list(pages)[30], poll.choices[0])
    assert s.screen.lecture is not None and s.screen.lecture.index == stop


def test_a_new_run_clears_every_pages_selection_and_a_page_follows_the_presenters_until_it_selects():
    s = demo_session()
    room = Classroom(s)
    room.join("projector", "presenter")
    room.join("laptop", "class", "seat 1")
    cells = s.engine.current_points()
    room.click("projector", tuple(cells[2]))
    assert s.view(room.state("laptop")).selected == 2  # it follows the presenter's selection
    room.click("laptop", tuple(cells[5]))
    assert s.view(room.state("laptop")).selected == 5 and s.view().selected == 2
    s.reset()
    assert room.state("laptop").selected is None and s.presenter.selected is None


def test_the_presenter_code_makes_a_class_page_present_and_only_five_tries_count():
    s = demo_session()
    room = Classroom(s)
    room.join("laptop", "class", "seat 1")
    room.join("other", "class", "seat 2")
    assert "not the presenter code" in room.claim_presenter("other", "0" * len(room.roles.code))
    for _ in range(4):
        room.claim_presenter("other", "1" * len(room.roles.code))
    assert "too many" in room.claim_presenter("other", room.roles.code)  # its five tries are used up
    assert "presents" in room.claim_presenter("laptop", room.roles.code)
    assert room.is_presenter("laptop") and room.may_drive("laptop") and room.laptop("laptop") is None
    assert s.screen.seats_here == frozenset({"seat 2"})  # a presenter's seat is not asked


def test_the_play_clock_refreshes_each_of_sixty_class_pages_six_times_a_second_while_playing():
    s = demo_session()
    room = Classroom(s)
    room.join("projector", "presenter")
    keys = ["projector", *_class(room)]
    refreshed = {k: 0 for k in keys}
    for _ in range(FPS):  # one second of frames, each showing a change (the run plays)
        due = room.due(keys, changed=True)
        assert "projector" in due and len(due) <= 1 + 360 / FPS
        for k in due:
            refreshed[k] += 1
    assert refreshed.pop("projector") == FPS
    assert set(refreshed.values()) == {6}  # CLASS_REFRESHES shared: 360 a second, 6 each


def test_a_change_to_a_paused_run_reaches_every_class_page_a_few_pages_a_frame():
    """200 pages beside a paused run: a step (one change) is brought to each of them once, twelve a
    frame, the presenter's page at once; then frames bring nothing more until the next change. Before,
    every frame refreshed every page (86 ms a frame at 200 pages, docs/PERFORMANCE.md)."""
    s = demo_session()
    room = Classroom(s, seats=Seats(per_address=200))
    room.join("projector", "presenter")
    keys = ["projector", *_class(room, 200)]
    assert room.due(keys, changed=False) == ["projector"]  # nothing changed: no class page's turn
    seen: list[str] = []
    frames = 0
    changed = True
    while frames == 0 or room.turns.owing:
        due = room.due(keys, changed)
        changed = False
        assert due[0] == "projector" and len(due) <= 1 + 360 / FPS
        seen += due[1:]
        frames += 1
    assert sorted(seen) == sorted(keys[1:]) and frames == 200 * FPS // 360 + 1  # each once, in 0.6 s
    room.due(keys, changed=True)  # a second change mid-way: the pages not yet reached keep their place
    first = room.due(keys, changed=True)[1:]
    assert first and first[0] not in room.due(keys, changed=False)


def test_a_page_that_acts_is_brought_up_to_date_first():
    s = demo_session()
    room = Classroom(s, seats=Seats(per_address=200))
    keys = list(_class(room, 200))
    room.due(keys, changed=True)
    room.turns.hurry(keys[-1])  # the last of the line tapped an answer
    assert keys[-1] in room.due(keys, changed=False)  # in the next frame, not 0.55 s later
