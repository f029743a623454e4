"""The visualiser's Session, without a browser: stepping, time travel, manual picks, edits, files."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from apf_viz.core.formats import InputError
from apf_viz.core.portrayal import Cells, Frame, Line
from apf_viz.ui.app import demo_session
from apf_viz.workbench.session import Session

START = [(0, 0), (0, 2), (1, 0), (1, 3)]
PATTERN = [(0, 0), (1, 0), (2, 0), (3, 0)]


def session(**kw) -> Session:
    return Session(START, PATTERN, y_up=[True] * 4, **kw)


def test_step_back_seek_and_branch():
    s = session()
    for _ in range(30):
        assert s.step()
    v = s.view()
    assert v.steps == 30 and v.event >= 30 and v.history_length == 30
    s.back()
    assert s.view().steps == 29 and s.view().history_length == 30
    s.seek(10)
    assert s.view().steps == 10
    s.set_scheduler("Manual")
    robot = s.engine.history.steps[10].record.robots[0]
    other = (robot + 1) % 4
    s.click(s.engine.current_points()[other])  # a different choice from step 10: a branch
    assert s.view().history_length == 11 and s.selected == other


def test_reset_rebuilds_the_start():
    s = session()
    for _ in range(40):
        s.step()
    s.reset()
    v = s.view()
    assert v.steps == 0 and [r.position for r in v.robots] == START


def test_manual_click_runs_the_robots_next_phase():
    s = session(scheduler="manual")
    p = s.engine.current_points()[2]
    assert s.click(p) == "robot 2: look"
    assert s.click(p) == "robot 2: compute"
    assert s.view().robots[2].phase == "computed"
    assert s.click(p) == "robot 2: move"
    assert s.view().robots[2].phase == "idle"
    assert s.click((50, 50)) == "nothing here" and s.selected is None


def test_in_other_schedulers_a_click_selects_and_shows_rays():
    s = session()
    s.click(START[3])
    v = s.view()
    assert v.selected == 3
    assert {b for _, b in v.rays} == {(0, 2), (1, 0), (0, 0)}  # (1, 3) sees all three


def test_ghosts_show_a_stale_snapshot():
    s = session(scheduler="manual")
    s.click(START[2])  # robot 2 looks
    s.click(START[0])  # robot 0 (terminal on L_1) looks, computes and moves left
    s.click(START[0])
    s.click(START[0])
    assert s.engine.current_points()[0] == (-1, 0)
    s.selected = 2
    v = s.view()
    assert [g[:3] for g in v.ghosts] == [((0, 0), "off", 0)]  # where robot 2 saw robot 0, in the light seen
    assert (
        "Stale" in v.caption
        and "robot 0: seen at (0, 0), now at (-1, 0); seen with light off, now terminal1" in v.caption
    )
    assert ((1, 0), (0, 0)) in v.rays and ((1, 0), (-1, 0)) not in v.rays  # rays go to what it saw


def test_the_caption_lists_every_difference_with_robot_names_and_idle_rays_show_the_present():
    s = session(scheduler="manual")
    s.click(START[3])  # robot 3 at (1, 3) looks: it sees robots 0, 1 and 2
    assert s.engine.state.seen[3] == (0, 1, 2)
    for _ in range(3):
        s.click(START[0])  # robot 0 moves left
    for _ in range(2):
        s.click(START[1])  # robot 1 looks and computes (its light may change)
    s.selected = 3
    v = s.view()
    seen = {b for _, b in v.rays}
    assert seen == {START[0], START[1], START[2]}  # the snapshot's places, though robot 0 is elsewhere
    changed = [line for line in v.caption.splitlines() if line.startswith("· robot")]
    lights = s.engine.state.lights
    expected = 1 + (lights[1] != "off")
    assert len(changed) == expected and changed[0].startswith("· robot 0: seen at (0, 0), now at (-1, 0)")
    s.selected = 0  # robot 0 is idle again: its rays are what it would see now
    v = s.view()
    assert {b for _, b in v.rays} == {
        tuple(p) for p in (s.engine.current_points()[j] for j in s.engine.visible(0).tolist())
    }
    assert "would see if it looked now" in v.caption and v.ghosts == ()


def test_a_robot_seen_after_several_moves_is_placed_where_it_stood_at_the_look():
    s = Session([(0, 0), (3, 0), (5, 1), (2, 2)], [(0, 0), (1, 0), (2, 0), (0, 1)], algorithm="compact-left")
    s.set_scheduler("Manual")
    for _ in range(3):
        s.click((3, 0))  # robot 1 slides to (2, 0) before robot 2 looks
    s.click((5, 1))  # robot 2 looks: it sees robot 1 at (2, 0)
    for _ in range(3):
        s.click((2, 0))  # robot 1 slides again, to (1, 0)
    s.selected = 2
    v = s.view()
    assert ((2, 0), "off", 1) in [g[:3] for g in v.ghosts]
    assert "robot 1: seen at (2, 0), now at (1, 0)" in v.caption


def test_edit_pattern_toggles_cells_and_validates_the_size():
    s = session()
    s.set_mode("edit-pattern")
    s.clear_pattern()
    for cell in [(0, 0), (1, 0), (2, 0)]:
        s.click(cell)
    assert s.view().draft_count == 3
    problem = s.set_mode("run")
    assert problem and "3 points but there are 4 robots" in problem
    assert s.mode == "edit-pattern" and s.view().draft_count == 3  # nothing lost
    s.click((0, 1))
    s.click((5, 5))
    s.click((5, 5))  # toggled off again
    assert s.set_mode("run") is None
    assert sorted(s.pattern) == [(0, 0), (0, 1), (1, 0), (2, 0)] and s.view().steps == 0


def test_a_demo_loaded_over_a_drawing_keeps_it_for_undo_and_says_so():
    s = demo_session()
    s.load_scenario("Heart from 10 robots")
    assert s.take_kept_drafts_note() is None  # nothing was drawn: nothing to tell
    s.set_mode("edit-pattern")
    s.clear_pattern()
    for cell in [(0, 0), (1, 0), (2, 0)]:
        s.click(cell)
    drawn = list(s.editor.pattern)
    s.load_scenario("One robot on L1")  # over the unfinished drawing
    assert s.mode == "run" and len(s.editor.pattern) == 3 and s.editor.pattern != drawn
    note = s.take_kept_drafts_note()
    assert note and "Undo brings it back" in note and s.take_kept_drafts_note() is None  # told once
    s.set_mode("edit-pattern")
    assert s.transform("Undo") == "undone" and s.editor.pattern == drawn  # the drawing, back
    assert "3 points" in s.set_mode("run")  # refused: the drawing is still unfinished, and still there
    assert s.editor.pattern == drawn


def test_edit_robots_adds_flips_removes_and_rejects_an_unsolvable_start():
    s = session()
    s.set_mode("edit-robots")
    assert s.click((5, 5)) == "added robot (5, 5)"
    assert s.click((5, 5)) == "removed robot (5, 5)"  # one click, one change: flipping is its own tool
    s.set_tool("flip")
    s.click(START[0])
    assert s.editor.y_up[s.editor.robots.index(START[0])] is False
    s.set_tool("cell")
    s.click((0, 0))
    s.click((0, 2))  # removes two robots
    s.click((1, 0))  # removed
    s.editor.robots, s.editor.y_up = [(0, 0), (0, 1)], [True, True]
    s.editor.pattern = [(0, 0), (1, 0)]
    problem = s.set_mode("run")
    assert problem and "y = 0.5" in problem and s.view().axis == 0.5
    assert [r.position for r in s.view().robots] == [(0, 0), (0, 1)]  # the scene shows the draft
    s.editor.robots.append((3, 0))
    s.editor.y_up.append(False)
    s.editor.pattern.append((2, 0))
    assert s.set_mode("run") is None
    assert s.engine.k == 3 and s.engine.y_up == (True, True, False)


def test_uploads_bad_files_leave_the_run_untouched():
    s = session()
    for _ in range(12):
        s.step()
    before = s.view()
    for loader, content, message in [
        (s.load_pattern, b"{not json", "not valid JSON"),
        (s.load_robots, json.dumps({"robots": [[0, 0], [0, 0]]}).encode(), "duplicate robot"),
        (s.load_trace, b'{"format": "x"}', "format"),
        (s.load_pattern, b"\xff\xfe", "not UTF-8"),
        (s.load_pattern, b" " * 3_000_000, "too large"),
    ]:
        with pytest.raises(InputError, match=message):
            loader("f.json", content)
    after = s.view()
    assert after.steps == before.steps and after.robots == before.robots


def test_upload_a_pattern_of_the_wrong_size_keeps_it_as_a_draft():
    s = session()
    note = s.load_pattern("p.json", json.dumps({"points": [[0, 0], [1, 1]]}).encode())
    assert s.mode == "edit-pattern" and s.view().draft_count == 2
    assert "2 points for 4 robots" in note


def test_download_and_reupload_round_trip():
    s = session()
    for _ in range(60):
        s.step()
    trace = s.trace_file().encode()
    robots = s.robots_file().encode()
    pattern = s.pattern_file().encode()
    t = session()
    t.load_trace("t.jsonl", trace)
    assert t.engine.history.length == 60
    t.seek(60)
    assert t.view().robots == s.view().robots
    u = session()
    u.load_pattern("p.json", pattern)
    u.load_robots("r.json", robots)
    assert u.robots == s.robots and u.pattern == s.pattern


def test_view_shows_the_algorithms_overlays_K_leader_frame_targets_and_stats():
    s = Session(
        [(0, 0), (0, 2), (1, 0), (1, 2), (2, 5)], [*PATTERN, (4, 0)], y_up=[True] * 5, scheduler="fsync"
    )
    seen_K = seen_frame = False
    stages = []
    while not s.engine.finished:
        s.step()
        v = s.view()
        stages.append(v.stage)
        seen_K |= any(isinstance(m, Line) and m.label == "K" for m in v.overlays.marks)
        frame = next((m for m in v.overlays.marks if isinstance(m, Frame)), None)
        cells = next(m for m in v.overlays.marks if isinstance(m, Cells))
        if frame is not None:
            seen_frame = True
            oy, sign = frame.origin[1], frame.y_sign
            assert cells.style == "placed" and cells.points == v.targets
            assert len(v.targets) == 5 and all(sign * (y - oy) >= 1 for _, y in v.targets)
        elif cells.style == "preview":
            assert cells.label == "pattern, not yet placed"
    v = s.view()
    assert seen_K and seen_frame and v.outcome == "formed" and v.stage.startswith("Formed")
    assert stages[0].startswith("Phase 1") and any(st.startswith("Phase 3") for st in stages)
    assert sorted(v.targets) == sorted(r.position for r in v.robots)  # formed: the targets stay under them
    assert v.moves_per_kD > 0 and v.move_series[-1][1] == v.moves


def test_demo_session_is_the_built_in_demo():
    s = demo_session()
    assert s.engine.k == 10 and len(s.pattern) == 10


def test_a_start_that_is_the_pattern_is_formed_at_once_even_when_symmetric():
    symmetric = [(0, 0), (0, 1), (2, 0), (2, 1)]  # mirror-symmetric about y = 0.5 (Theorem 1)
    s = Session(symmetric, [(5, 6), (5, 5), (7, 6), (7, 5)], y_up=[True] * 4)
    assert s.view().outcome == "formed" and not s.step()
    s = Session(START, PATTERN, y_up=[True] * 4)
    s.set_mode("edit-robots")
    s.editor.robots, s.editor.y_up = list(symmetric), [True] * 4
    s.set_mode("edit-pattern")
    s.editor.pattern = [(1, 1), (1, 2), (3, 1), (3, 2)]
    assert s.set_mode("run") is None  # not refused as unsolvable: it is already formed
    assert s.view().outcome == "formed" and s.view().moves == 0
    s.set_mode("edit-pattern")
    s.editor.pattern = [(0, 0), (1, 0), (2, 0), (3, 0)]
    assert "unsolvable" in s.set_mode("run")


def test_why_says_when_the_robots_a_decision_saw_have_changed_since():
    s = Session([(0, 0), (3, 0), (5, 1), (2, 2)], [(0, 0), (1, 0), (2, 0), (0, 1)], algorithm="compact-left")
    s.set_scheduler("Manual")
    for _ in range(2):
        s.click((5, 1))  # robot 2 looks and computes (slide left), seeing robot 1 at (3, 0)
    s.selected = 2
    assert s.view().why.changed == ()
    for _ in range(3):
        s.click((3, 0))  # robot 1 looks, computes, moves to (2, 0)
    s.selected = 2
    why, caption = s.view().why, s.view().caption
    assert why.changed_robots == (1,) and "(3, 0)" in why.changed[0] and "(2, 0)" in why.changed[0]
    assert why.changed[0] in caption  # one notion of staleness: the caption says it in the same words
    assert s.view().stale == (1,)


def test_a_snapshot_is_stale_only_when_another_robot_it_saw_changed():
    s = demo_session()
    s.set_scheduler("Manual")
    r = 1
    s.click(s.engine.current_points()[r])  # Look
    s.click(s.engine.current_points()[r])  # Compute: only its own light may change
    assert "Stale" not in s.view().caption and "the snapshot is current" in s.view().caption
    other = next(q for q in range(10) if q != r and q in s.engine.state.seen[r])
    for _ in range(3):  # the other robot looks, computes and moves (or stays)
        s.click(s.engine.current_points()[other])
    s.selected = r
    moved = s.engine.current_points()[other] != s.engine.start[other]
    relit = s.engine.state.lights[other] != "off"
    assert ("Stale" in s.view().caption) == (moved or relit)


def test_last_event_says_who_did_what_and_the_last_actor_is_marked():
    s = Session([(0, 0), (3, 0), (5, 1), (2, 2)], [(0, 0), (1, 0), (2, 0), (0, 1)], algorithm="compact-left")
    s.set_scheduler("Manual")
    s.click((5, 1))
    v = s.view()
    assert v.last_events[0] == "robot 2 · Look: sees 3 robots" and v.last_actor == 2
    s.click((5, 1))
    assert s.view().last_events[0] == "robot 2 · Compute: stays off, move left — compact-left.slide"
    s.click((5, 1))
    v = s.view()
    assert v.last_events[:3] == (
        "robot 2 · Move → (4, 1) on the grid",
        "robot 2 · Compute: stays off, move left — compact-left.slide",
        "robot 2 · Look: sees 3 robots",
    )


def test_a_compute_says_the_light_it_left_and_a_flipped_robots_move_in_both_frames():
    # Robot 1's y-axis is flipped: "down" in its frame is up on screen.
    s = Session([(0, 0), (0, 2)], [(0, 0), (0, 1)], y_up=[True, False], algorithm="compact-left")
    s.set_scheduler("Manual")
    s.click((0, 0))
    s.click((0, 0))  # robot 0: nothing to its left or below: done, a light change
    assert s.view().last_events[0] == "robot 0 · Compute: off → done, stay — compact-left.done"
    from apf_viz.core.grid import Direction
    from apf_viz.workbench.view_model.story import move_words

    assert move_words(Direction.UP, y_up=False) == "move down (its own frame; up on screen)"
    assert move_words(Direction.LEFT, y_up=False) == "move left"
    assert move_words(None, y_up=True) == "stay"


def test_next_move_and_next_stage_run_until_something_happens():
    s = demo_session()
    forever = float("inf")  # no time budget: the test asserts what happens, not how fast
    message = s.run_until("move", seconds=forever)
    assert s.engine.state.moves == 1 and message == f"a robot moved after {s.engine.step_index:,} steps"
    stage = s.view().stage
    message = s.run_until("stage", seconds=forever)
    assert s.view().stage != stage and message.startswith(s.view().stage)
    before = s.engine.step_index
    assert s.run_until("stage", seconds=-1.0) == "still no new stage after 1 step: press again"
    assert s.engine.step_index == before + 1  # a spent budget stops after one step, whatever the clock
    s.set_scheduler("Manual")
    assert "Manual" in s.run_until("move")


def test_the_move_of_a_decision_to_stay_is_said_to_stay():
    s = Session([(0, 0), (3, 0), (5, 1), (2, 2)], [(0, 0), (1, 0), (2, 0), (0, 1)], algorithm="compact-left")
    s.set_scheduler("Manual")
    for _ in range(3):
        s.click((0, 0))  # the leftmost robot: nothing to its left, so it stays (and shows done)
    assert s.view().last_events[0] == "robot 0 · Move: stays at (0, 0) on the grid"


def test_a_collision_is_located_in_words_and_cells():
    from pathlib import Path

    trace = Path(__file__).parent / "literal_traces" / "collision.jsonl"
    s = demo_session()
    s.load_trace(trace.name, trace.read_bytes())
    while s.engine.redo() is not None:  # follow the trace to its end
        pass
    v = s.view()
    assert v.outcome == "collision" and v.collision is not None
    words, cells = v.collision
    last = [ev for ev in s.engine.history.steps[s.engine.step_index - 1].events if ev.collision]
    r = last[0].robot
    x, y = last[0].to
    assert words.startswith(f"robot {r} moved onto robot ") and f"at ({x}, {y})" in words
    assert "on a snapshot taken at step" in words
    # The burst is where the collision is, not on the mover, whose move is drawn into it.
    assert last[0].to in cells and v.robots[r].position not in cells
    assert v.robots[r].pending == last[0].to


def test_robot_numbers_are_on_for_few_robots_and_can_be_switched():
    s = demo_session()
    assert s.view().numbers
    s.set_numbers(False)
    assert not s.view().numbers
    many = Session([(x, x % 7) for x in range(60)], [(x, 0) for x in range(60)])
    assert not many.view().numbers


def test_a_loaded_trace_is_followed_by_step_until_its_end_then_branch_here_leaves_it():
    from pathlib import Path

    from apf_viz.core.formats import load_trace

    path = Path(__file__).parent / "literal_traces" / "collision.jsonl"
    _, recorded = load_trace(path)
    s = demo_session()
    s.load_trace(path.name, path.read_bytes())
    assert s.view().trace_position == (0, len(recorded))
    while s.step():  # Step follows the trace, whatever the scheduler would choose
        pass
    v = s.view()
    assert v.outcome == "collision" and v.trace_position == (len(recorded), len(recorded))
    assert [e._replace(rule_id=None) for e in s.engine.history.events()] == recorded
    s.seek(10)
    assert s.step() and s.engine.history.length == len(s.engine.history.steps)  # still the trace
    assert s.view().trace_position is not None
    s.branch_here()
    assert s.view().trace_position is None
    s.set_scheduler("Manual")
    s.click(s.engine.current_points()[0])  # a person's choice from here on
    assert s.engine.step_index == 12


def test_a_manual_click_leaves_a_followed_trace():
    from pathlib import Path

    path = Path(__file__).parent / "literal_traces" / "collision.jsonl"
    s = demo_session()
    s.load_trace(path.name, path.read_bytes())
    s.set_scheduler("Manual")
    assert s.step()  # Step still follows the trace in Manual
    s.click(s.engine.current_points()[3])
    assert s.view().trace_position is None


def test_a_start_of_another_size_gets_a_demo_pattern_of_its_size_and_says_so():
    s = demo_session()  # 10 robots, the heart
    start = json.dumps({"robots": [[0, 0], [0, 2], [1, 0], [1, 2], [3, 0], [3, 1], [3, 2]]}).encode()
    note = s.load_robots("seven.json", start)
    assert s.mode == "run" and s.engine.k == 7 and len(s.config.pattern) == 7
    assert "the demo pattern cup-7" in note and "pattern had 10 points" in note
    eleven = json.dumps({"robots": [[i, i * i % 7] for i in range(11)]}).encode()  # no demo has 11 points
    note = s.load_robots("eleven.json", eleven)
    assert s.mode == "edit-robots" and "11 robots" in note  # kept as a draft; the size is the problem


def test_edit_robots_shows_the_drafted_pattern_not_the_runs():
    s = session()
    s.set_mode("edit-pattern")
    placed = list(s.editor.pattern)  # drawn beside the robots, never over them
    assert min(x for x, _ in placed) > max(x for x, _ in s.editor.robots)
    s.click((50, 50))  # the drafted pattern now has a fifth point
    s.set_mode("edit-robots")
    cells = s.view().overlays.marks[0]
    assert isinstance(cells, Cells) and (50, 50) in cells.points and cells.style == "preview"
    assert set(s.view().targets) == set(placed) | {(50, 50)}


def test_every_demo_scenario_loads_and_says_what_it_shows():
    from apf_viz.demos import scenarios

    for name, scenario in scenarios().items():
        s = demo_session()
        shows = s.load_scenario(name)
        assert shows.startswith(scenario.shows)
        v = s.view()
        if scenario.trace:
            assert v.trace_position == (0, s.run.trace_events) and v.trace_note
        elif "Unsolvable" in name:
            assert v.mode == "edit-robots" and v.axis is not None and "unsolvable" in shows
        else:
            assert v.mode == "run" and len(s.config.pattern) == s.engine.k
    with pytest.raises(InputError, match="no demo called"):
        demo_session().load_scenario("../../etc/passwd")


def test_each_scenario_run_shows_what_its_text_promises():
    from apf_viz.demos import scenarios

    for name, scenario in scenarios().items():
        if not scenario.fires:
            continue
        s = demo_session()  # the visualiser's default adversary: ASYNC, seed 1
        s.load_scenario(name)
        while s.step():
            pass
        fired = {ev.rule_id for ev in s.engine.history.events() if ev.phase == "compute"}
        assert s.engine.outcome == "formed" and set(scenario.fires) <= fired, (
            name,
            set(scenario.fires) - fired,
        )


def test_a_scenario_runs_its_own_algorithm_and_an_unsolvable_one_starts_afresh_in_edit_robots():
    s = demo_session()
    s.load_scenario("The literal paper deadlocks")
    while s.step():
        pass
    assert s.view().outcome == "stuck" and s.algorithm_name == "apf-opaque-grid-literal"
    s.load_scenario("Heart from 10 robots")
    assert s.algorithm_name == "apf-opaque-grid" and s.view().scenario_note.startswith("the paper end to end")
    s.load_scenario("The literal paper deadlocks")
    while s.step():
        pass
    s.load_scenario("Unsolvable box")
    v = s.view()
    assert v.mode == "edit-robots" and v.event == 0 and v.outcome is None and v.trace_position is None
    assert v.never_act == () and v.scenario_note.startswith("Theorem 1")
    # Play and Step say why nothing runs, naming the drafts' problem (not only "switch to Run": Run
    # would refuse these robots too).
    said = s.toggle_play()
    assert said.startswith("Play runs in Run mode") and "unsolvable start" in said and not s.playing
    assert not s.step() and "unsolvable start" in s.why_not_step()
    s.editor.robots[0] = (0, 1)  # move one robot onto the axis: solvable
    assert s.why_not_step() == "Step runs in Run mode: switch Mode back to Run"
    assert s.set_mode("run") is None and s.view().scenario_note == ""  # the text no longer applies
    assert s.toggle_play() is None and s.playing


def test_the_literal_collision_scenario_ends_located_after_41_events():
    s = demo_session()
    s.load_scenario("The literal paper collides")
    assert s.run.trace_events == 41
    while s.step():
        pass
    v = s.view()
    assert v.outcome == "collision" and v.event == 41
    assert v.collision[0].startswith("robot 3 moved onto robot 1 at (0, 1)")
    assert "verdict: collision" in v.trace_note


def test_a_deadlock_rings_every_robot_that_will_never_act():
    s = demo_session()
    s.load_scenario("The literal paper deadlocks")
    assert s.view().never_act == ()
    while s.step():
        pass
    v = s.view()
    assert v.outcome == "stuck" and v.never_act == tuple(range(s.engine.k))
    from apf_viz.workbench.view_model.why import why_markdown

    s.selected = 0
    assert "If it looked now:" in why_markdown(s.view().why) and "would change nothing" in why_markdown(
        s.view().why
    )


def test_a_livelock_from_check_marks_its_loop_on_the_timeline():
    from apf_viz.workbench.view_model.story import loop_marks

    # The explorer's schedule: 5 steps of stem, then a loop of 4 steps written twice: 13 steps.
    assert loop_marks({"loop_starts_at_step": 5}, 13, "async") == (
        (5, "loop starts"),
        (9, "loop repeats"),
        (13, "…for ever"),
    )
    assert loop_marks({"loop_starts_at_step": 1}, 9, "ssync") == (
        (3, "loop starts"),
        (6, "loop repeats"),
        (9, "…for ever"),
    )
    assert loop_marks({}, 13, "async") == () and loop_marks({"loop_starts_at_step": "x"}, 13, "async") == ()


def test_a_branch_sets_the_recorded_future_aside_and_return_goes_back_to_it():
    s = session(scheduler="manual")
    for r in (0, 0, 0, 1, 1):
        s.click(s.engine.current_points()[r])
    recorded = s.engine.history.events()
    s.back()
    s.back()  # at step 3: robot 1's Look and Compute are the recorded future
    s.click(s.engine.current_points()[2])  # a different choice: a branch
    v = s.view()
    assert v.branches == ("#1: left at step 3, 2 step(s), stopped at event 5",)
    assert s.engine.history.length == 4
    branch = s.engine.history.events()
    s.return_to_set_aside()
    v = s.view()
    assert v.steps == 3 and v.trace_position is not None and v.following_what == "branch #1"
    while s.step():  # Step follows the set-aside steps to their end
        pass
    assert s.engine.history.events() == recorded
    assert s.view().branches == ("#2: left at step 3, 1 step(s), stopped at event 4",)  # the line left
    s.return_to_set_aside()
    while s.step():
        pass
    assert s.engine.history.events() == branch
    with pytest.raises(InputError, match="no branch"):
        Session(START, PATTERN).return_to_set_aside()


def test_no_branch_is_lost_branch_return_branch_again_and_both_are_re_entered():
    """Branch at step 20, return to the trunk, branch again at step 30: both branches are kept, listed
    with where they left and how they end, and each is re-entered to exactly its own steps."""
    s = session(scheduler="async", seed=3)
    for _ in range(40):
        assert s.step()
    trunk = s.engine.history.events()
    s.seek(20)
    s.set_scheduler("round-robin")  # another adversary from here: a different line
    for _ in range(8):
        s.step()
    first = s.engine.history.events()
    assert first[: len(trunk)] != trunk
    s.return_to_set_aside()  # back on the trunk …
    while s.step():
        if s.engine.step_index >= 40:
            break
    assert s.engine.history.events() == trunk
    s.seek(30)
    s.branch_here()  # leave the followed line: the scheduler chooses
    s.set_scheduler("fsync")  # every robot at once: surely not the trunk's step
    for _ in range(5):
        s.step()  # … and a second branch off it, at step 30
    second = s.engine.history.events()
    labels = s.view().branches
    assert len(labels) == 2
    assert "left at step 20, 8 step(s), stopped at event 28" in labels[0]  # the first branch
    assert "left at step 30, 10 step(s), stopped at event 40" in labels[1]  # the trunk's rest
    for label, events in ((labels[0], first), (labels[1], trunk)):
        number = int(label[1:].split(":")[0])
        s.return_to_set_aside(number)
        while s.step():
            pass
        assert s.engine.history.events() == events
    assert len(s.view().branches) == 2  # entering one kept the line left: still two besides this one
    assert second in _lines_of(s)


def _lines_of(s: Session) -> list:
    """The events of every kept branch, each entered in turn (the line left each time kept)."""
    lines = []
    for label in s.view().branches:
        s.return_to_set_aside(int(label[1:].split(":")[0]))
        while s.step():
            pass
        lines.append(s.engine.history.events())
    return lines


def test_back_a_cycle_undoes_the_last_actors_look_compute_and_move():
    s = session(scheduler="manual")
    for r in (0, 1, 0, 0):  # robot 0: Look, (robot 1: Look), Compute, Move
        s.click(s.engine.current_points()[r])
    said = s.back_cycle()
    assert "robot 0" in said and s.engine.step_index == 0  # before robot 0's Look, robot 1's too
    s.seek(2)
    s.back_cycle()  # the last actor at step 2 is robot 1, whose Look was step 1
    assert s.engine.step_index == 1


def test_click_select_inspects_without_advancing_in_manual():
    s = session(scheduler="manual")
    s.set_click_advances(False)
    assert s.click(START[1]) == "selected robot 1" and s.engine.step_index == 0
    s.set_click_advances(True)
    assert s.click(START[1]).startswith("robot 1: look") and s.engine.step_index == 1


def test_notices_are_returned_to_the_caller_not_broadcast():
    s = session(scheduler="manual")
    assert not s.step() and s.why_not_step().startswith("Manual: click a robot")
    with pytest.raises(InputError, match="outside the grid"):
        s.click((10**13, 0))
    assert not hasattr(s, "messages")


def test_all_activations_restarts_the_run_keeping_every_cycle_and_the_panel_counts_what_was_skipped():
    s = demo_session()
    for _ in range(30):
        s.step()
    assert s.engine.skip_noops and s.view().skipped > 0
    s.set_all_activations(True)
    assert not s.engine.skip_noops and s.view().event == 0
    for _ in range(30):
        s.step()
    assert s.view().skipped == 0
    s.set_all_activations(False)
    assert s.engine.skip_noops and s.config.skip_noops


def test_download_schedule_after_manual_clicks_then_upload_it_on_a_reset_run_replays_them():
    s = demo_session()
    s.set_scheduler("Manual")
    for r in (2, 2, 2, 5, 5):
        s.click(s.engine.current_points()[r])
    clicked = s.engine.history.events()
    text = s.schedule_file()
    assert text.splitlines()[1:3] == ['{"robot": 2, "phase": "look"}', '{"robot": 2, "phase": "compute"}']
    s.reset()
    assert s.load_schedule("s.jsonl", text.encode()) is None
    v = s.view()
    assert v.trace_position == (0, len(clicked)) and v.following_what == "the schedule s.jsonl"
    while s.step():
        pass
    assert s.engine.history.events() == clicked
    bad = text + '{"robot": 0, "phase": "move"}\n'
    said = s.load_schedule("bad.jsonl", bad.encode())
    assert "bad.jsonl:7: robot 0's next phase is look, not move" in said
    assert s.run.trace_events == len(clicked)  # the run follows the schedule up to the bad line
    with pytest.raises(InputError, match="a schedule for 4 robots"):
        s.load_schedule("four.jsonl", b'{"format": "apf-viz-schedule", "version": 1, "robots": 4}\n')


def _first_differing_decision(s: Session) -> int:
    """The first differing decision of the run and its Compare twin, by a diff of their two event lists
    made here: the 1-based number of the first Compute whose rule, pending move or light differs."""
    twin = s.screen.twin.engine
    run_events, twin_events = s.engine.history.events(), twin.history.events()
    for n, (a, b) in enumerate(zip(run_events, twin_events, strict=False), 1):
        assert (a.robot, a.phase) == (b.robot, b.phase)  # the same schedule
        if a.phase == "compute" and (a.rule_id, a.move, a.light) != (b.rule_id, b.move, b.light):
            return n
    raise AssertionError("no decision differs")


def test_compare_steps_a_second_algorithm_with_the_run_and_names_the_first_divergence():
    from apf_viz.core.formats import load_trace
    from apf_viz.core.schedule import schedule_of_trace, schedule_text

    demos = Path(__file__).parent.parent / "demo_patterns"
    s = demo_session()
    s.load_robots("line.json", (demos / "starts" / "vertical-line-4.json").read_bytes())
    s.load_pattern("tee.json", (demos / "tee-4.json").read_bytes())
    assert s.algorithm_name == "apf-opaque-grid"  # A: the default, …
    header, events = load_trace(demos / "traces" / "literal-collision-4.jsonl")
    cex = schedule_text(4, schedule_of_trace(events, False))
    s.load_schedule("cex.jsonl", cex.encode())  # … under the adversary that breaks the literal paper
    s.compare_with("apf-opaque-grid-literal")  # B: the literal paper, stepping with it
    while s.step():
        pass
    v = s.view()
    assert v.compare is not None and v.compare.outcome == "collision" and v.outcome != "collision"
    assert v.compare.event <= v.event and v.divergence is not None
    at, what, robot, then = v.divergence
    assert at == _first_differing_decision(s) and what.startswith(f"robot {robot} · Compute")
    assert then.count("Move") == 2 and then.startswith(f"robot {robot} ")  # the move that follows, both
    assert v.diverged == robot and v.compare.diverged == robot  # marked in both runs
    s.seek(0)
    v = s.view()
    assert v.compare.event == 0 and v.divergence is None  # back in time: before the divergence
    s.compare_with(None)
    assert s.view().compare is None
    with pytest.raises(ValueError):
        s.compare_with("os:abort")


@pytest.mark.parametrize("spread", [False, True])
def test_play_at_speed_walks_and_records_the_same_run_as_stepping(spread):
    """Play with a large allowance per call (the render loop's budget at a high speed) takes walks and
    forced cycles (core/fast_forward.py), yet records the very steps Step does, one by one."""
    import random

    from apf_viz.algorithms.apf_opaque_grid.audit import random_pattern, random_solvable_start

    rng = random.Random(5)
    start = random_solvable_start(20, rng)
    if spread:
        start = [(x * 40 + rng.randrange(40), y * 40 + rng.randrange(40)) for x, y in start]
    pattern = random_pattern(20, rng)
    stepped, played = Session(start, pattern, seed=3), Session(start, pattern, seed=3)
    while not stepped.engine.finished:
        stepped.step()
    played.toggle_play()
    calls = 0
    while played.playing:
        taken = played.play_steps(150)
        assert 0 <= taken <= 150
        calls += 1
    assert played.engine.outcome == stepped.engine.outcome == "formed"
    assert played.engine.history.events() == stepped.engine.history.events()
    assert calls * (10 if spread else 2) < played.engine.step_index  # many steps per call: walks
    for s in (played, stepped):
        s.seek(s.engine.step_index // 2)  # the timeline goes back inside them
    assert played.engine.current_points() == stepped.engine.current_points()
    a, b = played.view(), stepped.view()
    assert (a.robots, a.stage, a.event, a.moves) == (b.robots, b.stage, b.event, b.moves)


def test_compare_goes_on_with_the_run_beside_it_once_the_run_is_over():
    """A run that ends first (the literal paper's collision) leaves the run beside it mid-way: Step then
    goes on with that one alone, under the run's scheduler and seed, to its own end; Back drops what it
    did alone."""
    from apf_viz.core.formats import load_trace
    from apf_viz.core.schedule import schedule_of_trace, schedule_text

    demos = Path(__file__).parent.parent / "demo_patterns"
    s = demo_session()
    s.load_robots("line.json", (demos / "starts" / "vertical-line-4.json").read_bytes())
    s.load_pattern("tee.json", (demos / "tee-4.json").read_bytes())
    s.set_algorithm("apf-opaque-grid-literal")  # A: the literal paper, which collides …
    header, events = load_trace(demos / "traces" / "literal-collision-4.jsonl")
    s.load_schedule("cex.jsonl", schedule_text(4, schedule_of_trace(events, False)).encode())
    s.compare_with("apf-opaque-grid")  # … B: the default, which does not
    steps = 0
    while s.step():
        steps += 1
        assert steps < 100_000
    v = s.view()
    assert v.outcome == "collision" and v.compare is not None and v.compare.outcome == "formed"
    assert v.compare.event > v.event  # the run beside it went on past the collision
    assert "the run beside it is over too" in s.why_not_step()
    s.seek(3)
    assert s.view().compare.event == s.view().event  # Back: the steps it took alone are dropped


def test_every_downloaded_trace_is_the_run_with_its_verdict():
    """Right after a trace (a counterexample) loads, the file is the whole trace with its verdict; once
    the run has left it, the file is the run so far with its outcome, and no panel speaks of the trace."""
    from apf_viz.core.formats import load_trace

    demos = Path(__file__).parent.parent / "demo_patterns"
    path = demos / "traces" / "literal-collision-4.jsonl"
    s = demo_session()
    s.load_trace(path.name, path.read_bytes())
    assert s.engine.step_index == 0 and "verdict: collision" in s.view().trace_note
    out = Path(__file__).parent / "_downloaded.jsonl"
    try:
        out.write_text(s.trace_file())
        header, events = load_trace(out)
        _, original = load_trace(path)
        assert events == original and header.options["verdict"] == "collision"
        assert header.options["shown_at_event"] == 0
        for _ in range(10):
            s.step()
        s.branch_here()  # leave the trace: the scheduler chooses from here
        assert s.view().trace_note == "" and "The trace" not in s.view().trace_line
        s.step()
        out.write_text(s.trace_file())
        header, events = load_trace(out)
        assert len(events) == s.engine.state.events and header.options["verdict"] == "running"
        while s.step():
            pass
        out.write_text(s.trace_file())
        header, events = load_trace(out)
        assert header.options["verdict"] == s.engine.state.outcome and len(events) == s.engine.state.events
    finally:
        out.unlink(missing_ok=True)


def test_step_at_the_end_of_a_followed_branch_says_so_and_a_canvas_edit_is_said():
    s = session(scheduler="async", seed=3)
    for _ in range(10):
        s.step()
    s.seek(5)
    s.set_scheduler("fsync")
    s.step()  # every robot at once: a branch
    s.return_to_set_aside()
    while s.step():
        pass
    assert "ends here" in s.why_not_step() and "Branch here" in s.why_not_step()
    s.set_mode("edit-pattern")
    said = s.click((40, 40))
    assert said == "added target (40, 40)" == s.screen.studio.said  # the line under the tool


def test_a_manual_click_that_is_the_traces_next_step_follows_it_still():
    """Found replaying a breaking schedule: a click on the robot the trace moves next took the "Following
    the trace" line away, though the run was still the trace's; a click on another robot leaves it."""
    from pathlib import Path

    path = Path(__file__).parent / "literal_traces" / "collision.jsonl"
    s = demo_session()
    s.load_trace(path.name, path.read_bytes())
    s.set_scheduler("Manual")
    assert s.step()
    recorded = s.engine.history.steps[s.engine.step_index]  # the trace's next step
    (robot,) = recorded.record.robots
    s.click(s.engine.current_points()[robot])
    assert s.view().trace_position is not None and s.run.following
    nxt = s.engine.history.steps[s.engine.step_index].record.robots[0]
    other = next(r for r in range(s.engine.k) if r != nxt)
    s.click(s.engine.current_points()[other])
    assert s.view().trace_position is None and not s.run.following


def test_a_branch_keeps_its_number_whichever_line_is_the_runs():
    """Found comparing lines: each time the line changed, the branches were numbered anew (#1 entered
    came back as #3). A line keeps its number: entering #1 sets the line left aside as #2; entering #2
    again sets #1 aside, by the same number."""
    s = session(scheduler="manual")
    for r in (0, 0, 0, 1, 1):
        s.click(s.engine.current_points()[r])
    s.back()
    s.back()
    s.click(s.engine.current_points()[2])
    assert [b.split(":")[0] for b in s.view().branches] == ["#1"]
    s.return_to_set_aside(1)
    assert [b.split(":")[0] for b in s.view().branches] == ["#2"]
    s.return_to_set_aside(2)
    assert [b.split(":")[0] for b in s.view().branches] == ["#1"]
    s.return_to_set_aside(1)
    assert [b.split(":")[0] for b in s.view().branches] == ["#2"]
