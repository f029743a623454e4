"""Guided lectures (issue #24): the file format, the stops a session walks through, and the check a
lecturer runs the evening before."""

from __future__ import annotations

import json

import pytest

from apf_viz.cli import main
from apf_viz.core.formats import InputError
from apf_viz.demos import demo_files
from apf_viz.lecture import lectures, parse_lecture
from apf_viz.ui.app import demo_session

SHIPPED = demo_files("lectures")


def lecture_json(**stop) -> str:
    first = {"title": "start", "say": "words", "scenario": "Heart from 10 robots"}
    stops = [first] + ([{"title": "next", "say": "more", **stop}] if stop else [])
    return json.dumps({"format": "apf-viz-lecture", "version": 1, "title": "t", "stops": stops})


@pytest.mark.parametrize("name", sorted(SHIPPED))
def test_each_shipped_lecture_passes_the_check(name, capsys):
    assert main(["lecture", "check", str(SHIPPED[name])]) == 0
    out = capsys.readouterr().out
    assert "NOT" not in out and out.strip().endswith("stops reached, their claims true")
    assert "claim(s) hold" in out  # the shipped lectures state their claims


def test_the_shipped_lectures_are_the_issues_two_at_least():
    assert {
        "The algorithm in 12 stops",
        "Where the paper breaks under ASYNC",
        "What a robot cannot see",
    } <= set(lectures())
    assert len(lectures()["The algorithm in 12 stops"].stops) == 12


def shipped_json(name: str) -> dict:
    return json.loads(SHIPPED[name].read_text())


@pytest.mark.parametrize(
    ("stop", "expect", "said"),
    [
        (3, {"lights": {"decider": 1}}, "expects 1 robot(s) lit decider, the screen shows 2"),
        (
            2,
            {"drawn": ["the leader's frame"]},
            "expects “the leader's frame” drawn, the marks are “K”, “pattern",
        ),
        (11, {"state": "stuck"}, "expects the run stuck, it is formed"),
        (4, {"stage": "Phase 3"}, "expects the stage “Phase 3”"),
        (0, {"sees": 3}, "expects what the selected robot sees, but no robot is selected"),
    ],
)
def test_an_edited_claim_fails_the_check_and_says_what_the_screen_shows(tmp_path, capsys, stop, expect, said):
    data = shipped_json("algorithm-in-12-stops")
    data["stops"][stop]["expect"] = expect
    edited = tmp_path / "edited.json"
    edited.write_text(json.dumps(data))
    assert main(["lecture", "check", str(edited)]) == 1
    out = capsys.readouterr().out
    assert f"NOT stop {stop + 1}:" in out and said in out
    assert out.count("NOT") == 1  # the other stops' claims still hold


def test_a_stop_selecting_a_robot_the_run_does_not_have_fails_the_check(tmp_path, capsys):
    """Found by a first-time lecturer: select 9 on a five-robot run passed as ok, selecting nothing."""
    bad = tmp_path / "select.json"
    bad.write_text(lecture_json(select=10))  # the heart has robots 0-9
    assert main(["lecture", "check", str(bad)]) == 1
    assert "selects robot 10, but the run has 10 robots (0–9)" in capsys.readouterr().out


def test_the_check_shows_each_stop_in_the_words_a_claim_takes(capsys):
    """A lecturer writes claims from what the check shows: the stage, the lights, the marks, the state,
    and what a selected robot sees."""
    assert main(["lecture", "check", "what-a-robot-cannot-see"]) == 0
    out = capsys.readouterr().out
    assert "shows: stage “Phase 1: leader election (Algorithm 1) — every robot off”; lights off 10; " in out
    assert "marks “pattern, not yet placed”; state running; robot 0 sees 8, 1 hidden" in out


def test_the_docs_example_stage_stops_where_its_words_hold():
    """LECTURES.md's example, ``until: {"stage": "symmetric about K"}``, once stopped at a half-way stage
    whose name held the same words (one robot lit symmetric, K not drawn): it stops at the pair now."""
    from collections import Counter

    from apf_viz.lecture import Lecture, Stop, Until

    s = demo_session()
    s.start_lecture(
        Lecture(
            format="apf-viz-lecture",
            version=1,
            title="t",
            stops=[
                Stop(title="a", say="b", scenario="Symmetric R_I: deciders"),
                Stop(title="c", say="d", until=Until(stage="symmetric about K")),
            ],
        )
    )
    s.next_stop()
    assert Counter(s.engine.state.lights)["symmetric"] == 2
    assert "K" in [m.label for m in s.view().overlays.marks]


def test_lectures_md_names_every_scenario_light_and_stage_a_lecture_can_use():
    """A lecture names scenarios, lights, marks and stages by their exact words: the manual lists them
    all (a first-time lecturer had to find them in the repository)."""
    from pathlib import Path

    from apf_viz.algorithms import get_algorithm
    from apf_viz.algorithms.apf_opaque_grid import portrayal
    from apf_viz.demos import scenarios

    doc = " ".join((Path(__file__).resolve().parent.parent / "docs" / "LECTURES.md").read_text().split())
    missing = [name for name in scenarios() if f"`{name}`" not in doc]
    missing += [light for light in get_algorithm("apf-opaque-grid").lights if f"`{light}`" not in doc]
    missing += [words for words in ("two deciders stand on L_1", "L_1's terminal pair is symmetric about K")
                if words not in doc]  # fmt: skip
    missing += [label for label in ("K", "targets", "the leader's frame", "pattern, not yet placed")
                if f"`{label}`" not in doc]  # fmt: skip
    assert not missing and portrayal.STAGES[1] in doc, missing


def test_words_that_send_the_room_to_a_panel_fail_the_check(tmp_path, capsys):
    """Presentation mode hides the panel: "the Paper panel shows…" names what the room cannot see."""
    data = shipped_json("algorithm-in-12-stops")
    data["stops"][1]["say"] += " The Paper panel shows the line it used."
    edited = tmp_path / "edited.json"
    edited.write_text(json.dumps(data))
    assert main(["lecture", "check", str(edited)]) == 1
    assert "its words name “The Paper panel”, which presentation mode hides" in capsys.readouterr().out


def test_words_that_name_a_light_no_robot_shows_fail_the_check(tmp_path, capsys):
    """The 12-stop lecture's third stop once said "both terminal1" over two robots lit symmetric: words
    claiming a light ("lit L", "lights L", "L robots") that no robot shows at the stop fail the check;
    a light named in passing ("were terminal1") does not."""
    from apf_viz.lecture import claimed_lights

    lights = ("off", "terminal1", "symmetric", "leader1", "leader")
    assert claimed_lights("Both terminal1 robots stand on a line", lights) == ["terminal1"]
    assert claimed_lights("then lit decider; it lights leader", (*lights, "decider")) == ["leader", "decider"]
    assert claimed_lights("the robot that was leader1 turns to face", lights) == []
    data = shipped_json("algorithm-in-12-stops")
    data["stops"][2]["say"] = "Both terminal1 robots stand on one vertical line."
    edited = tmp_path / "edited.json"
    edited.write_text(json.dumps(data))
    assert main(["lecture", "check", str(edited)]) == 1
    out = capsys.readouterr().out
    said = "its words say a robot is lit terminal1; none is at this stop (they show 8 off, 2 symmetric)"
    assert said in out


def test_a_shipped_lecture_is_checked_by_its_name_as_a_wheel_user_would(capsys):
    assert main(["lecture", "check", "where-the-paper-breaks"]) == 0
    assert main(["lecture", "check", "The algorithm in 12 stops"]) == 0


def test_a_stage_is_named_only_when_the_configuration_shows_it():
    """The 12-stop lecture's fourth stop once said "two deciders" while one robot was lit decider: the
    stage was named on the first decider. Now every event of the run is checked."""
    from collections import Counter

    s = demo_session()
    while s.step():
        lights = Counter(s.engine.state.lights)
        stage = s.view().stage
        if "two deciders" in stage:
            assert lights["decider"] == 2, (s.engine.state.events, lights)
        if "terminal pair is symmetric" in stage:
            assert lights["symmetric"] == 2, (s.engine.state.events, lights)
    assert s.engine.outcome == "formed"


def test_after_play_or_a_step_past_a_stop_the_caption_says_where_the_run_is():
    s = demo_session()
    s.start_lecture(lectures()["The algorithm in 12 stops"])
    stop = lectures()["The algorithm in 12 stops"].stops[0]
    assert s.view().lecture == ("stop 1 of 12 · The algorithm in 12 stops", stop.title, stop.say)
    s.step()
    where, title, words = s.view().lecture
    assert where == "away from stop 1 of 12 · The algorithm in 12 stops" and stop.say not in words
    assert title == "Played on from stop 1 — event 1"
    assert "PageDown: stop 2, “Phase 1: the terminals of L_1”" in words and "PageUp: back to stop 1" in words
    s.toggle_play()
    assert s.view().lecture[1].startswith("Playing on from stop 1")
    s.pause()
    s.previous_stop()  # off the stop, PageUp goes back to it
    assert s.lecturer.position == 0 and s.view().lecture[2] == stop.say
    s.next_stop()
    s.next_stop()
    s.back()
    _, title, words = s.view().lecture
    assert title.startswith("Stepped back from stop 3") and "PageUp: back to stop 3" in words
    s.seek(s.lecturer.mark.step)  # back on the stop's own step (its question recorded the run past it)
    assert s.view().lecture[2] == lectures()["The algorithm in 12 stops"].stops[2].say


def test_a_stop_that_is_never_reached_fails_the_check_with_exit_1(tmp_path, capsys):
    bad = tmp_path / "late.json"
    bad.write_text(lecture_json(until={"stage": "a stage no algorithm names"}))
    assert main(["lecture", "check", str(bad)]) == 1
    out = capsys.readouterr().out
    assert "NOT stop 2" in out and "the run ended (formed)" in out


@pytest.mark.parametrize(
    ("stop", "said"),
    [
        (
            {"until": {"event": 3, "stage": "x"}},
            "stops[1].until: give exactly one of event, stage, rule, outcome",
        ),
        ({"scenario": "../../etc/passwd"}, "stops[1]: no Demo scenario called '../../etc/passwd'"),
        ({"until": {"outcome": "exploded"}}, "stops[1].until.outcome:"),
        ({"select": -1}, "stops[1].select:"),
        ({"script": "rm -rf /"}, "stops[1].script:"),
        # A number is a number: a string, a truth value or a float is the author's mistake, never 0.
        ({"ask": {"kind": "light", "robot": "0"}}, "stops[1].ask.robot: Input should be a valid integer"),
        ({"ask": {"kind": "light", "robot": True}}, "stops[1].ask.robot: Input should be a valid integer"),
        ({"ask": {"kind": "light", "robot": 0.0}}, "stops[1].ask.robot: Input should be a valid integer"),
        ({"select": "2"}, "stops[1].select: Input should be a valid integer"),
        ({"until": {"event": 3.0}}, "stops[1].until.event: Input should be a valid integer"),
        ({"class_address": 1}, "stops[1].class_address: Input should be a valid boolean"),
    ],
)
def test_a_malformed_lecture_is_one_line_naming_the_field_and_exit_2(tmp_path, capsys, stop, said):
    bad = tmp_path / "bad.json"
    bad.write_text(lecture_json(**stop))
    with pytest.raises(SystemExit) as exit_:
        main(["lecture", "check", str(bad)])
    assert exit_.value.code == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and said in err and "Traceback" not in err


def test_next_and_previous_stop_walk_the_session_and_replay_from_the_scenario():
    s = demo_session()
    s.start_lecture(lectures()["The algorithm in 12 stops"])
    assert s.view().lecture[0] == "stop 1 of 12 · The algorithm in 12 stops"
    events = []
    for _ in range(4):
        s.next_stop()
        events.append(s.engine.state.events)
    assert events == sorted(events) and s.view().lecture[0].startswith("stop 5 of 12")
    s.previous_stop()  # replayed from the heart's start: the same event as when it was reached
    assert s.engine.state.events == events[-2] and s.view().lecture[0].startswith("stop 4 of 12")
    assert s.view().lecture[2] == s.screen.lecture.say  # the view carries the words to the caption
    s.start_lecture(None)
    assert s.view().lecture is None


def test_an_uploaded_lecture_that_is_malformed_keeps_the_run_and_the_lecture():
    s = demo_session()
    s.start_lecture(lectures()["The algorithm in 12 stops"])
    s.next_stop()
    before = (s.engine.state.events, s.screen.lecture)
    with pytest.raises(InputError, match=r"mine\.json: stops"):
        s.load_lecture("mine.json", lecture_json(until={}).encode())
    with pytest.raises(InputError, match="not UTF-8"):
        s.load_lecture("mine.json", b"\xff\xfe")
    assert (s.engine.state.events, s.screen.lecture) == before
    said = s.load_lecture("mine.json", lecture_json(until={"rule": "A1.off.terminal"}).encode())
    assert said.startswith("stop 1") and s.view().lecture[0] == "stop 1 of 2 · t"


def test_parse_lecture_refuses_a_first_stop_without_a_scenario():
    text = json.dumps(
        {"format": "apf-viz-lecture", "version": 1, "title": "t", "stops": [{"title": "a", "say": "b"}]}
    )
    with pytest.raises(InputError, match="the first stop names a scenario"):
        parse_lecture(text)


@pytest.mark.parametrize("label", list(__import__("apf_viz.lecture", fromlist=["figures"]).figures()))
def test_each_figure_of_the_paper_holds_at_its_stated_event(label):
    from collections import Counter

    from apf_viz.lecture import figures

    figure = figures()[label]
    s = demo_session()
    said = s.start_lecture(figure.as_lecture())
    assert "not reached" not in said and s.engine.state.events == figure.event
    assert dict(Counter(s.engine.state.lights)) == figure.lights, figure.caption
    assert s.view().lecture[2] == figure.caption  # the caption on screen
    pts, lights = s.engine.current_points(), list(s.engine.state.lights)
    for claim in figure.positions:
        assert POSITION_CLAIMS[claim](pts, lights, s), (label, claim)


def _with(light, pts, lights):
    return [p for p, lt in zip(pts, lights, strict=True) if lt == light]


def _pair_on_one_vertical_line(light):
    def holds(pts, lights, s):
        pair = _with(light, pts, lights)
        return len(pair) == 2 and pair[0][0] == pair[1][0]

    return holds


def _compact_line(pts, lights, s):
    (lx, ly) = _with("leader", pts, lights)[0]
    xs = sorted(x for x, y in _with("off", pts, lights) if y == ly)
    return xs == list(range(lx + 1, lx + 1 + len(_with("off", pts, lights))))


def _one_side(pts, lights, s):
    (_, ly) = _with("leader", pts, lights)[0]
    sides = {(y > ly) - (y < ly) for _, y in _with("off", pts, lights)}
    return len(sides) == 1 and 0 not in sides


def _robot_on_K(pts, lights, s):
    from apf_viz.algorithms.apf_opaque_grid.portrayal import line_K

    k = line_K(tuple(pts), tuple(lights))
    return k is not None and any(y == k for _, y in pts)


# The captions' words about positions, as checks of the configuration at the figure's event.
POSITION_CLAIMS = {
    "terminal1-left-of-the-rest": lambda pts, lights, s: all(
        x < min(p[0] for p, lt in zip(pts, lights, strict=True) if lt != "terminal1")
        for x, _ in _with("terminal1", pts, lights)
    ),
    "a-robot-on-K": _robot_on_K,
    "terminal1-pair-on-one-vertical-line": _pair_on_one_vertical_line("terminal1"),
    "decider-pair-on-one-vertical-line": _pair_on_one_vertical_line("decider"),
    "others-on-one-side-of-the-leaders-row": _one_side,
    "compact-line-beside-the-leader": _compact_line,
    "the-pattern-formed": lambda pts, lights, s: s.engine.outcome == "formed",
}


def test_every_position_claim_of_a_figure_is_a_known_check():
    from apf_viz.lecture import figures

    claims = {c for f in figures().values() for c in f.positions}
    assert claims and claims <= set(POSITION_CLAIMS)


def test_the_example_in_docs_lectures_passes_the_check(tmp_path, capsys):
    import re
    from pathlib import Path

    doc = (Path(__file__).parents[1] / "docs" / "LECTURES.md").read_text(encoding="utf-8")
    example = tmp_path / "example.json"
    example.write_text(re.search(r"```json\n(.*?)```", doc, re.S).group(1))
    assert main(["lecture", "check", str(example)]) == 0
    assert "3 of 3 stops reached" in capsys.readouterr().out


def test_serve_with_a_bad_lecture_stops_before_the_ui_with_one_line(tmp_path):
    import subprocess
    import sys

    bad = tmp_path / "bad.json"
    bad.write_text(lecture_json(until={"outcome": "exploded"}))
    done = subprocess.run(
        [sys.executable, "-m", "apf_viz.cli", "serve", "--port", "0", "--lecture", str(bad)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 2
    assert done.stderr.strip().count("\n") == 0 and "stops[1].until.outcome" in done.stderr


def test_at_a_compare_stop_whose_run_is_over_enter_steps_and_space_plays_the_run_beside_it():
    """Stop 6 of "Where the paper breaks" (Resolution G1): the run on the left is stuck; its words say
    Space plays the run on the right on to FORMED. Enter steps it one event; Space plays it (the same
    scheduler and seed) to its end; then Step says where each side stands."""
    s = demo_session()
    lecture = lectures()["Where the paper breaks under ASYNC"]
    s.start_lecture(lecture)
    for _ in range(5):
        s.next_stop()
    assert s.lecturer.position == 5 and s.engine.outcome == "stuck"
    assert "Space plays it on to FORMED" in lecture.stops[5].say
    before = s.view()
    assert before.compare is not None and before.compare.outcome is None
    assert s.step()  # the left run is over; the right one takes a step
    after = s.view()
    assert after.event == before.event and after.compare.event == before.compare.event + 1
    s.toggle_play()
    assert s.playing
    for _ in range(100_000):
        if not s.play_steps(10):
            break
    end = s.view().compare
    assert end.outcome == "formed" and not s.playing  # as the stop's words say
    said = s.why_not_step()
    assert said.startswith("the run is over (stuck)")
    assert f"the run beside it is over too, at event {end.event} ({end.outcome})" in said


@pytest.mark.parametrize("moved", ["play", "step", "back", "branch"])
def test_pagedown_after_the_run_moved_lands_where_pagedown_alone_lands(moved):
    """Before, Play at stop 3 and then PageDown showed stop 4's words over the formed heart (event 542):
    the next stop ran on from wherever the run had gone. Now it starts from the stop's own state."""
    lecture = lectures()["The algorithm in 12 stops"]
    alone = demo_session()
    alone.start_lecture(lecture)
    for _ in range(3):
        alone.next_stop()
    s = demo_session()
    s.start_lecture(lecture)
    s.next_stop()
    s.next_stop()  # stop 3
    if moved == "play":
        for _ in range(400):
            if not s.step():
                break
    elif moved == "step":
        s.step()
    elif moved == "back":
        s.back()
    else:  # back, then a step the history did not record: a branch drops the stop's future
        scheduler = s.run.config.scheduler
        s.seek(0)
        s.set_scheduler("round-robin")
        s.step()
        s.step()
        s.set_scheduler(scheduler)
    s.next_stop()
    assert s.engine.state.events == alone.engine.state.events
    assert s.engine.current_points() == alone.engine.current_points()
    assert s.view().lecture == alone.view().lecture


def test_lecture_check_refuses_a_46_word_stop_naming_it(tmp_path, capsys):
    """45 words fit a projector's caption at 20 px; the 46th is refused, in one line naming the stop."""
    fits = tmp_path / "fits.json"
    fits.write_text(lecture_json(say=" ".join(["word"] * 45)))
    assert main(["lecture", "check", str(fits)]) == 0
    long = tmp_path / "long.json"
    long.write_text(lecture_json(say=" ".join(["word"] * 46)))
    with pytest.raises(SystemExit) as ended:
        main(["lecture", "check", str(long)])
    err = capsys.readouterr().err
    assert ended.value.code == 2 and "stops[1].say: 46 words; a stop says at most 45" in err
    assert len(err.strip().splitlines()) == 1


@pytest.mark.parametrize(
    ("stop", "said"),
    [
        # The merged-light stop as it once was: "no leader" over a stage line that elects one.
        (
            {"until": {"stage": "leader elected"}, "say": "The robots wait, with no leader elected."},
            "its words say no leader was elected, the stage line says “Phase 2",
        ),
        # A stop whose expect claims a stage while the run is stuck: the stage line names the outcome.
        (
            {
                "scenario": "The literal paper deadlocks",
                "until": {"outcome": "stuck"},
                "say": "A deadlock.",
                "expect": {"state": "stuck", "stage": "walking to its corner"},
            },
            "expects the stage “walking to its corner”, the stage line says “STUCK: no robot will act again”",
        ),
        (
            {"until": {"stage": "9 of 9 robots lined up"}, "say": "A compact line from (1, −1) to (9, −1)."},
            "its words give (1, −1) in no named frame",
        ),
    ],
)
def test_lecture_check_fails_words_the_stage_line_or_frame_contradict(tmp_path, capsys, stop, said):
    bad = tmp_path / "bad.json"
    bad.write_text(lecture_json(**stop))
    assert main(["lecture", "check", str(bad)]) == 1
    assert said in capsys.readouterr().out


def test_words_that_agree_with_the_stage_line_and_name_their_frame_pass(tmp_path):
    good = tmp_path / "good.json"
    good.write_text(
        lecture_json(
            until={"stage": "9 of 9 robots lined up"},
            say="A compact line from (1, −1) to (9, −1) in the leader's frame; a leader was elected.",
        )
    )
    assert main(["lecture", "check", str(good)]) == 0


def test_an_authors_right_to_left_controls_never_reorder_the_pages_own_words():
    """A stop's words with an unclosed right-to-left override (U+202E) are closed and set apart as an
    isolate: the caption's words after them (the stage line, the stop's number) keep their order. Plain
    left-to-right words are kept exactly; right-to-left words are kept, set apart."""
    evil = "look \u202eright here"
    text = lecture_json(say=evil, title="ti\u2067tle", ask={"kind": "outcome", "text": "\u202bwhat?"})
    lecture = parse_lecture(text, "evil.json")
    stop = lecture.stops[1]
    assert stop.say == "\u2068" + evil + "\u202c\u2069" and stop.title == "\u2068ti\u2067tle\u2069\u2069"
    assert stop.ask is not None and stop.ask.text == "\u2068\u202bwhat?\u202c\u2069"
    assert lecture.stops[0].say == "words"  # left-to-right: as written
    hebrew = parse_lecture(lecture_json(say="שלום לכולם"), "he.json").stops[1].say
    assert hebrew == "\u2068שלום לכולם\u2069"
    s = demo_session()
    s.load_lecture("evil.json", text.encode())
    s.next_stop()
    s.next_stop()
    shown = " ".join(s.view().lecture or ())
    assert "\u2068" + evil + "\u202c\u2069" in shown


def test_colour_words_are_held_to_what_the_stop_draws(tmp_path, capsys):
    """The words "the grey squares" at the stuck stop of "Where the paper breaks" are the robots that
    will never act; the same words at its first stop (nothing stuck yet) fail the check, and so do
    "robots drawn blue" at the last stop of the 12-stop lecture, where every robot is done (green)."""
    from apf_viz.workbench.colour_words import claimed_colours, colour_name
    from apf_viz.workbench.palette import MARK_COLORS

    assert [colour_name(MARK_COLORS[m]) for m in ("never", "ray", "selected", "collision", "last")] == [
        "grey", "yellow", "black", "magenta", "brown",
    ]  # fmt: skip
    assert claimed_colours("a thin gray line; robots drawn in Blue; the old light named blue") == [
        ("gray line", "grey", "line"),
        ("drawn in Blue", "blue", "any"),
    ]
    data = shipped_json("where-the-paper-breaks")
    data["stops"][0]["say"] += " The grey squares are robots that will never act."
    edited = tmp_path / "grey.json"
    edited.write_text(json.dumps(data))
    assert main(["lecture", "check", str(edited)]) == 1
    out = capsys.readouterr().out
    assert "its words say “grey squares”; no grey square is drawn at this stop" in out
    assert out.count("grey squares") == 1  # the stuck stop's own words hold: grey squares are drawn there
    data = shipped_json("algorithm-in-12-stops")
    data["stops"][-1]["say"] += " The robots drawn blue are done."
    edited.write_text(json.dumps(data))
    assert main(["lecture", "check", str(edited)]) == 1
    assert "its words say “drawn blue”; nothing blue is drawn at this stop (green" in capsys.readouterr().out
