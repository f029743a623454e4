"""A lecture stop's question (issue #58): its answer is what the run does from the stop, found again here
from the run's events by a reading of our own; the room's answers are held one a page, changed until the
reveal, and the reveal plays the run to the answer."""

from __future__ import annotations

import json
import random

import pytest

from apf_viz.cli import main
from apf_viz.core.formats import InputError
from apf_viz.lecture import Question, find_lecture, parse_lecture
from apf_viz.workbench.lecturer import Lecturer
from apf_viz.workbench.poll import MAX_ANSWERS, Poll
from apf_viz.workbench.question import answer
from apf_viz.workbench.session import Session

HEART = "algorithm-in-12-stops"


def events_after(session: Session, start: int) -> list:
    """Every event of the run from step ``start`` on, played to its end."""
    e = session.engine
    while session.step():
        pass
    return [ev for step in e.history.steps[start:] for ev in step.events]


def first_answers(session: Session, start: int, k: int) -> dict[str, set[str]]:
    """Each question's answer read from the events: the first step with a Move that changes a cell, each
    robot's first such Move, its first new light, the outcome."""
    e = session.engine
    e.seek(start)
    at = {i: tuple(map(int, p)) for i, p in enumerate(e.positions)}
    light = {i: e.state.lights[i] for i in range(k)}
    out: dict[str, set[str]] = {}
    for step in e.history.steps[start:]:
        movers = {ev.robot for ev in step.events if ev.phase == "move" and tuple(ev.to) != at[ev.robot]}
        if movers and "robot" not in out:
            out["robot"] = {str(r) for r in movers}
        for ev in step.events:
            if ev.phase == "move" and tuple(ev.to) != at[ev.robot]:
                out.setdefault(f"cell{ev.robot}", {f"{ev.to[0]},{ev.to[1]}"})
                if not ev.collision:
                    at[ev.robot] = tuple(ev.to)
            if ev.phase == "compute" and ev.light is not None and ev.light != light[ev.robot]:
                out.setdefault(f"light{ev.robot}", {ev.light})
                light[ev.robot] = ev.light
    return out


@pytest.mark.parametrize("name", [HEART, "where-the-paper-breaks"])
def test_every_answer_is_what_the_run_then_does(name):
    """At every stop of two shipped lectures, every question of every kind about every robot: the answer
    the run gives equals what its events show when it is played to its end."""
    lecture = find_lecture(name)
    session = Session([(0, 0)], [(0, 0)])
    lecturer = Lecturer(session, lecture)
    checked = 0
    for index in range(len(lecture.stops)):
        lecturer.go(index)
        e = session.engine
        k, start = e.k, e.step_index
        questions = [Question(kind="robot"), Question(kind="outcome")]
        questions += [Question(kind=kind, robot=r) for kind in ("cell", "light") for r in range(k)]
        given = {q: answer(session, q) for q in questions}
        assert e.step_index == start  # each question leaves the run where the stop left it
        events_after(session, start)
        outcome = e.outcome
        expected = first_answers(session, start, k)
        for q, got in given.items():
            key = q.kind + ("" if q.robot is None else str(q.robot))
            want = {outcome} if q.kind == "outcome" and outcome not in (None, "limit") else expected.get(key)
            if want is None:
                assert isinstance(got, str), (index, key, got)
            else:
                assert not isinstance(got, str), (index, key, got)
                assert set(got.right) == want, (index, key)
                checked += 1
        lecturer.go(index)  # back where the stop leaves the run
    assert checked > 10


def test_lecture_check_prints_each_questions_answer(capsys):
    assert main(["lecture", "check", "where-the-paper-breaks"]) == 0
    out = capsys.readouterr().out
    assert "asks: Under this schedule, how does the run end? — the run answers collision (at event 41)" in out
    for name in (HEART, "what-a-robot-cannot-see"):
        assert main(["lecture", "check", name]) == 0
        assert "asks: " in capsys.readouterr().out
    for lecture in map(find_lecture, (HEART, "what-a-robot-cannot-see", "where-the-paper-breaks")):
        assert any(stop.ask is not None for stop in lecture.stops)


@pytest.mark.parametrize(
    ("stop", "said"),
    [
        ({"until": {"outcome": "formed"}, "ask": {"kind": "robot"}}, "ended (formed) before it answers"),
        ({"ask": {"kind": "light", "robot": 12}}, "asks about robot 12, but the run has 10 robots"),
    ],
)
def test_a_question_the_run_cannot_answer_fails_the_check(tmp_path, capsys, stop, said):
    first = {"title": "start", "say": "words", "scenario": "Heart from 10 robots"}
    bad = tmp_path / "bad.json"
    stops = [first, {"title": "asks", "say": "more", **stop}]
    bad.write_text(json.dumps({"format": "apf-viz-lecture", "version": 1, "title": "t", "stops": stops}))
    assert main(["lecture", "check", str(bad)]) == 1
    out = capsys.readouterr().out
    assert "NOT stop 2" in out and said in out and "has no answer" in out


@pytest.mark.parametrize(
    ("ask", "said"),
    [
        ({"kind": "cell"}, "stops[1].ask: a cell question names its robot"),
        ({"kind": "robot", "robot": 2}, "stops[1].ask: a robot question is about the whole run"),
        ({"kind": "colour"}, "stops[1].ask.kind"),
    ],
)
def test_a_malformed_question_is_refused_in_one_line(ask, said):
    first = {"title": "start", "say": "words", "scenario": "Heart from 10 robots"}
    stops = [first, {"title": "asks", "say": "more", "ask": ask}]
    with pytest.raises(InputError) as err:
        parse_lecture(json.dumps({"format": "apf-viz-lecture", "version": 1, "title": "t", "stops": stops}))
    assert said in str(err.value) and "\n" not in str(err.value)


def heart_at_question() -> Session:
    session = Session([(0, 0)], [(0, 0)])
    session.start_lecture(find_lecture(HEART))
    for _ in range(2):
        session.next_stop()
    assert session.screen.poll is not None
    return session


def test_answers_are_one_a_page_changed_until_the_reveal():
    session = heart_at_question()
    poll = session.screen.poll
    assert poll is not None and poll.kind == "robot"
    right = min(poll.answer.right, key=int)
    wrong = next(c for c in poll.choices or () if c not in poll.answer.right)
    session.answer_question("a", wrong)
    session.answer_question("a", right)  # changed: still one answer
    session.answer_question("b", right)
    session.answer_question("c", wrong)
    assert (poll.count, poll.right_count) == (3, 2)
    view = session.view().poll
    assert view is not None and view.bars == () and view.answer == ""  # the spread is not out yet
    session.toggle_spread()
    bars = {b.choice: b.count for b in session.view().poll.bars}
    assert bars[right] == 2 and bars[wrong] == 1 and sum(bars.values()) == 3
    with pytest.raises(InputError, match="is not an answer"):
        session.answer_question("d", "robot 99")
    session.reveal()
    with pytest.raises(InputError, match="takes no more answers"):
        session.answer_question("a", wrong)
    assert session.view().poll.answer == f"robot {right}"


def test_the_reveal_plays_the_run_to_the_answer_and_selects_the_mover():
    session = heart_at_question()
    poll = session.screen.poll
    assert poll is not None
    start = session.engine.step_index
    session.reveal()
    assert session.playing
    while session.play_steps(3):
        pass
    e = session.engine
    assert e.step_index == poll.answer.step > start and e.state.events == poll.answer.event
    assert not session.playing
    assert str(session.presenter.selected) in poll.answer.right


def test_a_click_answers_which_robot_and_where():
    session = heart_at_question()
    poll = session.screen.poll
    assert poll is not None
    cell = tuple(map(int, session.engine.positions[3]))
    assert session.answer_by_click("a", cell) is not None and poll.given("a") == "3"
    assert session.answer_by_click("a", (10_000, 10_000)) is None and poll.given("a") == "3"  # no robot there


def test_a_cell_answer_is_read_as_the_grid_reads_it():
    session = heart_at_question()
    poll = session.screen.poll
    assert poll is not None
    cells = Poll(poll.answer.__class__(Question(kind="cell", robot=0), frozenset({"2,-1"}), 1, 1), 10, ())
    assert cells.read(" (2, −1) ") == "2,-1" and cells.read("-3,4") == "-3,4"
    for bad in ("2", "a, b", "1e3, 2", "10000000000000, 1"):
        with pytest.raises(InputError):
            cells.read(bad)
    for i in range(MAX_ANSWERS):
        cells.give(str(i), "0,0")
    with pytest.raises(InputError, match="the most a question takes"):
        cells.give("one more", "0,0")
    cells.give("0", "1,1")  # a page that answered may still change its answer


def test_a_seat_is_read_only_from_a_seat_path_signed_by_this_server():
    from apf_viz.ui.seat import seat_token
    from apf_viz.workbench.seats import Seats

    seats, other = Seats(), Seats()
    token = seats.issue("10.0.0.7")
    assert seat_token(f"/seat/{token}") == token and seats.key(token) == "seat " + token.split("-")[0]
    number = token.split("-")[0]
    forged = [f"{number}-{'0' * 16}", other.issue("10.0.0.7"), token.upper(), token + "x", "../x", "", None]
    for made_up in forged:  # a page's own, another run's, a token bent: no seat
        assert seats.key(made_up) is None, made_up
    for path in (None, "/", f"/present/{token}"):
        assert seat_token(path) is None


def test_two_thousand_pages_from_one_address_with_fresh_or_forged_tokens_answer_as_one():
    """A client opening connection after connection: each comes with a token of its own making (no
    seat) or none, and is issued one; one address is issued one seat, so every page's answer lands on it."""
    from apf_viz.workbench.seats import Seats

    session = heart_at_question()
    seats = Seats()
    rng = random.Random(5)
    for i in range(2_000):
        made_up = f"{rng.getrandbits(64):016x}-{rng.getrandbits(64):016x}" if i % 2 else None
        key = seats.key(made_up) or seats.key(seats.issue("203.0.113.9"))  # the page goes to its seat
        session.answer_question(key, str(i % 3))
    assert session.screen.poll is not None and session.screen.poll.count == 1
    for address in ("203.0.113.10", "203.0.113.11"):  # another laptop: a seat of its own
        session.answer_question(seats.key(seats.issue(address)), "1")
    assert session.screen.poll.count == 3
    with pytest.raises(InputError, match="no seat yet"):
        session.answer_question(None, "1")


def test_a_hall_behind_one_router_has_the_seats_it_is_given_and_no_more():
    from apf_viz.workbench.seats import MAX_ADDRESSES, Seats

    seats = Seats(per_address=3)
    issued = [seats.issue("192.0.2.1") for _ in range(10)]
    assert len(set(issued)) == 3 and all(seats.key(t) for t in issued)  # a fourth page gets one of them
    assert len({seats.issue(None), seats.issue(None)}) == 2  # an unknown address is one address
    for n in range(MAX_ADDRESSES + 5):  # a scan from many addresses: the oldest forgotten
        seats.issue(f"a{n}")
    assert len(seats._issued) == MAX_ADDRESSES
    with pytest.raises(ValueError):
        Seats(per_address=0)


def test_a_stop_visited_again_keeps_the_rooms_answers():
    session = heart_at_question()
    poll = session.screen.poll
    assert poll is not None
    session.answer_question("a", "1")
    session.next_stop()
    assert session.screen.poll is None  # stop 4 asks nothing
    session.previous_stop()
    assert session.screen.poll is poll and poll.given("a") == "1"  # PageUp back: nobody answers twice


def test_a_class_pages_caption_says_its_own_answer_and_after_the_reveal_whether_it_was_right():
    """Found by a lecturer: after R a student in presentation mode saw only the run's answer, and after a
    reload the caption said "answer in the panel" though the answer was kept. Each class page's caption
    now says its own answer (under its seat: a reload keeps it), then right or not; never another's."""
    from apf_viz.workbench.view_model.caption import caption_html

    session = heart_at_question()
    poll = session.screen.poll
    assert poll is not None
    right = min(poll.answer.right, key=int)
    wrong = next(c for c in poll.choices or () if c not in poll.answer.right)
    session.answer_question("seat a", right)
    session.answer_question("seat b", wrong)

    def caption(seat: str, page: str = "following") -> str:
        return caption_html(session.view(), page, mine=poll.told(seat) if page != "presenting" else "")

    assert f"Your answer: robot {right}" in caption("seat a")  # a reload asks again, by its seat
    assert "answer in the panel" in caption("seat c")  # not answered
    assert f"robot {right}" not in caption("seat b").split("Question:")[1].split("(change")[0]
    session.reveal()
    assert f"You answered robot {right}: right" in caption("seat a")
    assert f"You answered robot {wrong}: not this time" in caption("seat b")
    assert "You did not answer" in caption("seat c")
    presenting = caption("seat a", "presenting")
    assert "You answered" not in presenting and "gave it" in presenting


def test_the_presenters_caption_counts_the_answers_of_the_seats_here():
    """ "2 of 5 answered": the seats connected now, and a seat that answered and left still among them;
    with no seats known (no server: an exported page, a script) the count alone."""
    from apf_viz.workbench.view_model.caption import caption_html

    session = heart_at_question()
    session.answer_question("seat a", "1")
    session.answer_question("seat gone", "0")
    assert "2 answered" in caption_html(session.view(), "presenting")
    session.seat_the_room(frozenset({"seat a", "seat b", "seat c", "seat d"}))
    assert "2 of 5 answered" in caption_html(session.view(), "presenting")
    assert "answered" not in caption_html(session.view(), "following")  # a class page never sees the count
