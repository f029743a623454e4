"""The view model (workbench/view_model): what each browser's screen says, tested without a browser,
by the facts its sentences carry (robot numbers, cells, rule ids), never by whole sentences."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

from apf_viz.core.formats import InputError
from apf_viz.ui.app import demo_session
from apf_viz.workbench.classroom import Classroom
from apf_viz.workbench.screen_state import BrowserState
from apf_viz.workbench.session import Session
from apf_viz.workbench.view_model import for_browser, present, present_run
from apf_viz.workbench.view_model.staleness import changes
from apf_viz.workbench.view_model.story import OUTCOME_ICONS

LITERAL_COLLISION = Path(__file__).parent / "literal_traces" / "collision.jsonl"


def played_to_its_end(scenario: str) -> Session:
    s = demo_session()
    s.load_scenario(scenario)
    while s.step():
        pass
    return s


def stale_session() -> Session:
    """Robot 2 looks and computes seeing robot 1 at (3, 0); then robot 1 moves to (2, 0)."""
    s = Session([(0, 0), (3, 0), (5, 1), (2, 2)], [(0, 0), (1, 0), (2, 0), (0, 1)], algorithm="compact-left")
    s.set_scheduler("Manual")
    for _ in range(2):
        s.click((5, 1))
    for _ in range(3):
        s.click((3, 0))
    s.selected = 2
    return s


def test_a_collision_names_its_robots_and_cell_in_the_banner():
    s = demo_session()
    s.load_trace(LITERAL_COLLISION.name, LITERAL_COLLISION.read_bytes())
    while s.engine.redo() is not None:
        pass
    v = s.view()
    crash = [ev for ev in s.engine.history.steps[s.engine.step_index - 1].events if ev.collision]
    mover, cell = crash[0].robot, crash[0].to
    onto = next(i for i, r in enumerate(v.robots) if r.position == cell and i != mover)
    assert set(v.collided) == {mover, onto}
    # The burst is on the cell moved into; the mover stands on its own, its move drawn into the burst.
    assert v.collision[1] == (cell,) and v.robots[mover].pending == cell
    assert "COLLISION" in v.banner and f"robot {mover}" in v.banner and f"robot {onto}" in v.banner
    assert f"({cell[0]}, {cell[1]})" in v.banner
    look = int(s.engine.state.look_step[mover])
    assert f"step {look}" in v.banner  # the snapshot it moved on


def test_the_stale_facts_name_the_robots_that_changed_and_where():
    s = stale_session()
    v = s.view()
    assert v.selected == 2 and v.stale == (1,)
    assert v.ghosts == (((3, 0), "off", 1, False),)  # where it was seen, in the light seen, numbered
    assert v.stale_holders == (2,)  # its mark, and no other robot's: none other holds a stale snapshot
    assert "robot 1" in v.caption and "(3, 0)" in v.caption and "(2, 0)" in v.caption
    assert "robot 0" not in v.caption.split("Stale")[-1]  # robot 0 did not change
    fresh = stale_session()
    fresh.click((5, 1))  # robot 2 moves: its cycle ends, it holds no snapshot
    fresh.selected = 2
    assert fresh.view().stale == () and fresh.view().ghosts == ()


def test_why_and_the_caption_use_one_notion_of_staleness():
    s = stale_session()
    v = s.view()
    assert v.why is not None and v.why.changed_robots == v.stale == (1,)
    for sentence in v.why.changed:
        assert sentence in v.caption  # the same words in both panels
    assert [c.robot for c in changes(s.engine, 2, "held")] == [1]
    assert [c.robot for c in changes(s.engine, 2, "decided")] == [1]
    assert "robot 1" in v.why_text and "(3, 0)" in v.why_text


def test_why_carries_the_rule_the_robot_computed_with():
    s = demo_session()
    for _ in range(30):
        s.step()
    e = s.engine
    computes = [ev for step in e.history.steps[: e.step_index] for ev in step.events if ev.phase == "compute"]
    last = computes[-1]
    s.selected = last.robot
    v = s.view()
    assert v.why.robot == last.robot and v.why.explanation.decision.rule_id == last.rule_id
    assert last.rule_id in v.why_text and f"Robot {last.robot}" in v.why_text
    assert v.why.explanation.decision.light == last.light


def test_each_browser_has_its_own_selection_and_a_follower_shows_the_presenters():
    s = demo_session()
    for _ in range(12):
        s.step()
    laptop = BrowserState()
    s.presenter.selected = 4
    run = present_run(s.run, s.screen)
    projector_view = for_browser(run, s.run, s.screen, s.presenter, s.presenter)
    laptop_view = for_browser(run, s.run, s.screen, laptop, s.presenter)
    assert projector_view.selected == 4 and projector_view.rays
    assert laptop_view.selected is None and laptop_view.rays == () and laptop_view.why is None
    laptop.follow = True
    followed = present(s.run, s.screen, laptop, s.presenter)
    assert followed.selected == 4 and followed.rays == projector_view.rays and followed.follows_presenter
    assert laptop.selected is None  # following shows the presenter's; it selects nothing of its own


def test_a_click_selects_for_the_browser_that_clicked_only():
    s = demo_session()
    room = Classroom(s)
    room.join("projector", "presenter")
    room.join("laptop", "presenter")
    cell = s.engine.current_points()[3]
    assert room.click("laptop", cell) == []
    assert s.view(room.state("laptop")).selected == 3 and s.view(room.state("projector")).selected is None
    s.reset()  # a new run clears every browser's selection
    assert s.view(room.state("laptop")).selected is None


def test_targets_stay_where_the_pattern_forms_at_every_event_of_the_demo():
    """The leader walks last, to t_{n−1}: the targets drawn do not walk with it (the done robots fix
    them); every done robot stands on a drawn target at every event, and at FORMED every robot does."""
    s = demo_session()
    off_target = []
    while s.step():
        v = s.view()
        targets = set(v.targets)
        lights = s.engine.state.lights
        off_target += [
            (v.event, i) for i, r in enumerate(v.robots) if lights[i] == "done" and r.position not in targets
        ]
    assert s.engine.outcome == "formed" and off_target == []
    assert {r.position for r in s.view().robots} == set(s.view().targets)


def test_the_demo_texts_match_their_runs():
    """What each Demo text says is drawn is drawn, when it says so."""
    s = demo_session()
    s.load_scenario("Heart from 10 robots")
    ks = set()
    while s.step():
        v = s.view()
        ks.add((v.stage.split(":")[0], any(m.label == "K" for m in v.overlays.marks)))
    assert ("Phase 3", True) not in ks  # the text does not promise K in Phase 3
    assert "leader's row" in s.scenario_note or "leader's row" in s.view().scenario_note
    s = demo_session()
    s.load_scenario("Robots already on K")
    assert not any(m.label == "K" for m in s.view().overlays.marks)  # not before the terminals light
    assert "once the two light terminal1" in s.view().scenario_note
    s = demo_session()
    s.load_scenario("The L2 lockstep counterexample")
    assert "escape" in s.view().scenario_note and "escape" in s.view().trace_note


def test_the_drafted_patterns_swatch_is_its_canvas_colour_and_formed_drops_phase_rings():
    from apf_viz.workbench.palette import TARGET_COLORS
    from apf_viz.workbench.view_model.legend import legend_html

    s = demo_session()
    s.set_mode("edit-pattern")
    v = s.view()
    (cells,) = [m for m in v.overlays.marks if m.label == "pattern being drawn"]
    assert cells.style == "drawing" and f"rgb{TARGET_COLORS['drawing']}" in legend_html(v)
    assert f"rgb{TARGET_COLORS['placed']}" not in legend_html(v)
    s = demo_session()
    while s.step():
        pass
    v = s.view()
    assert v.outcome == "formed" and not v.phase_rings and v.last_actor is None


def test_a_collision_is_explained_by_the_movers_stale_decision():
    s = played_to_its_end("The literal paper collides")
    v = s.view()
    assert v.outcome == "collision"
    mover = next(ev.robot for ev in s.engine.history.steps[s.engine.step_index - 1].events if ev.collision)
    why, computed = v.fatal
    look = int(s.engine.state.look_step[mover])
    assert computed is not None and look < computed < v.steps
    assert f"robot {mover} decided this move at step {computed}" in why and f"at step {look}" in why
    stale = [c for c in v.collided if c != mover]
    assert any(f"robot {r}: seen at" in why for r in stale)  # what changed since, named
    assert why in v.banner
    s.seek(computed)
    assert s.view().last_events[0].startswith(f"robot {mover} · Compute")  # the fatal decision itself


def test_go_to_divergence_lands_on_the_first_event_the_two_runs_differ():
    from tests.apf_helpers import compare_on_the_collision_counterexample

    s = compare_on_the_collision_counterexample(demo_session())
    at, what, robot, then = s.view().divergence
    assert then  # played on: the move that followed the decision, in both runs
    s.seek_event(at)
    v = s.view()
    assert v.event == at and v.divergence == (at, what, robot, "")  # its consequence is still to come
    assert v.last_events[0].startswith(
        f"robot {robot} · "
    )  # the run's side of the difference is the last event
    assert v.diverged == robot == v.compare.diverged  # marked in both runs


def test_a_deadlock_says_what_each_robot_waits_on():
    s = played_to_its_end("The literal paper deadlocks")
    v = s.view()
    assert v.outcome == "stuck"
    e = s.engine
    for r in range(e.k):  # each robot is listed once, with the rule it answers its view with now
        rule_id = e.decide(e.look(r)).rule_id
        line = next(line for line in v.waits.splitlines() if rule_id in line)
        listed = line.split(" — ")[0].removeprefix("robots ").removeprefix("robot ").split(", ")
        assert str(r) in listed
    assert sum(len(line.split(" — ")[0].split(", ")) for line in v.waits.splitlines()) == e.k
    assert v.waits in v.banner


def test_the_selected_robot_sees_what_it_hides_and_a_light_only_change_has_its_own_ghost():
    # Robots in a row: robot 0 sees robot 1 only; robot 1 hides robot 2 (and 2 hides 3 behind it).
    s = Session([(0, 0), (1, 0), (2, 0), (3, 0)], [(0, 0), (1, 0), (2, 0), (3, 0)], algorithm="compact-left")
    s.set_scheduler("Manual")
    s.selected = 0
    v = s.view()
    assert v.hidden == (2, 3) and v.hiders == ((1, 2), (1, 3))
    s.click((0, 0))  # robot 0 looks: it now holds a snapshot of robot 1 alone
    s.selected = 0
    assert s.view().hidden == (2, 3)


def test_a_robot_that_only_changed_light_leaves_a_badge_ghost():
    s = Session([(0, 0), (0, 3)], [(0, 0), (0, 1)], algorithm="compact-left")
    s.set_scheduler("Manual")
    s.click((0, 3))  # robot 1 looks: it sees robot 0 (off)
    s.click((0, 0))  # robot 0 looks: nothing to its left
    s.click((0, 0))  # robot 0 computes: it is done, a light change without a move
    s.selected = 1
    v = s.view()
    assert v.ghosts == (((0, 0), "off", 0, True),)  # on the robot itself: drawn as a badge
    assert v.stale_holders == (1,)


def _every_predicate_of_every_demo():
    from apf_viz.core.portrayal import explain
    from apf_viz.demos import scenarios

    found = {}
    for name in scenarios():
        s = demo_session()
        s.load_scenario(name)
        e = s.engine
        for _ in range(3000):
            if e.finished or not (s.step() if not s.run.following else e.redo() is not None):
                break
            for r in range(e.k):
                d = e.state.decided[r]
                if d is not None:
                    for p in explain(e.algorithm, d, e.pattern).predicates:
                        found[(p.symbol, p.value if isinstance(p.value, bool) else "·", p.meaning)] = p.value
    return found


def test_why_reads_every_test_of_every_demo_positively():
    from apf_viz.workbench.view_model.why import found_row

    predicates = _every_predicate_of_every_demo()
    assert sum(isinstance(v, bool) and not v for v in predicates.values()) > 10  # false tests are read
    for (symbol, _, meaning), value in predicates.items():
        found, test = found_row(symbol, value, meaning)
        if isinstance(value, bool):
            assert found.startswith("✔ ") and "not so:" not in found, (symbol, value, meaning, found)
            words = found.lower()
            assert not (words.startswith("✔ no ") and " not " in words), found  # no double negative
            assert "≠ ∅" not in found and "= ∅" not in found  # the symbols go to the test column


def test_a_trail_is_each_robots_last_moves_ending_where_it_stands():
    from apf_viz.workbench.view_model.story import trails

    s = demo_session()
    e = s.engine
    path: list[list] = [[p] for p in e.start]
    while e.step_index < 200:
        s.step()
        for r, p in enumerate(e.current_points()):
            if p != path[r][-1]:
                path[r].append(p)
    now = e.current_points()
    for moves in (1, 3, 8):
        got = trails(e, moves, now)
        for r in range(e.k):
            want = tuple(path[r][-(moves + 1) :]) if len(path[r]) > 1 else ()
            assert got[r] == want, (r, moves)
    assert trails(e, 0, now) == ()


def test_the_lockstep_escape_ends_with_a_banner_and_its_walk_drawn():
    s = demo_session()
    s.load_scenario("The L2 lockstep counterexample")
    assert s.view().banner == "" and any(s.view().trails) is False  # at its start: nothing walked yet
    s.seek(10**9)
    v = s.view()
    assert v.outcome is None and v.banner.startswith("## ↻ ESCAPE: it never ends")
    assert "robot 0 left the box at (-19, -1)" in v.banner
    walkers = [r for r, t in enumerate(v.trails) if t]
    assert walkers == [0, 1] and all(len(v.trails[r]) >= 20 for r in walkers)
    assert all(t[-1] == v.robots[r].position for r, t in enumerate(v.trails) if t)
    s.set_trails(0)  # the person's setting does not hide the walk of an endless trace
    assert s.view().trails == v.trails
    for bad in (-1, 51, float("nan"), 2.5e9):
        with pytest.raises(InputError):
            s.set_trails(bad)


@pytest.mark.parametrize(
    ("scenario", "said"),
    [
        ("The literal paper collides", "robot 3 decided this move at step 40 on what it saw at step 38"),
        ("The literal paper deadlocks", "A2.leader1.wait"),
        ("The L2 lockstep counterexample", "ESCAPE: it never ends"),
    ],
)
def test_presentation_modes_caption_explains_each_failure_at_its_end(scenario, said):
    from apf_viz.workbench.view_model.caption import caption_html

    s = demo_session()
    s.load_scenario(scenario)
    assert said not in caption_html(s.view(), details=True)
    s.seek(10**9)
    assert said in caption_html(s.view(), details=True)


def test_the_caption_names_every_light_in_use_and_keeps_their_meanings_for_the_details():
    """The words show the lights as one row of names; the details (I) give each its meaning, and the
    stage line names a stuck run's outcome, not the phase it was in."""
    from apf_viz.workbench.view_model.caption import caption_html

    s = demo_session()
    s.load_scenario("The literal paper deadlocks")
    s.seek(10**9)
    v = s.view()
    meaning = v.legend["off"].meaning
    words, details = caption_html(v), caption_html(v, details=True)
    assert v.outcome == "stuck" and meaning not in words and meaning in details
    assert set(v.lights_in_use) >= {"off", "terminal1", "leader1"}
    assert all(f"<b>{light}</b>" in words for light in v.lights_in_use)
    assert "STUCK" in words and "walking to its corner" not in words and "walking" in v.stage


@pytest.mark.skipif(shutil.which("fc-list") is None, reason="no fontconfig (fc-list)")
@pytest.mark.parametrize("outcome", sorted(OUTCOME_ICONS))
def test_the_outcome_banners_icon_is_in_a_font_this_machine_has(outcome):
    """The banner's icon must draw on a fresh machine (Debian's Chromium with its DejaVu fonts): the emoji
    it once used drew as empty boxes there."""
    code = f"{ord(OUTCOME_ICONS[outcome]):04x}"
    fonts = subprocess.run(["fc-list", f":charset={code}", "family"], capture_output=True, text=True).stdout
    assert fonts.strip(), f"no installed font draws U+{code.upper()} ({OUTCOME_ICONS[outcome]})"


def test_formed_upside_down_says_why_that_counts():
    """A pattern formed as its mirror image in y (the robots agree only on left and right) is FORMED,
    and the banner says the shape is the drawn one upside down and why that counts; one formed as drawn
    says nothing of the kind."""
    said = {}
    for scenario in ("Symmetric start that needs call", "Heart from 10 robots"):
        s = demo_session()
        s.load_scenario(scenario)
        while s.step():
            pass
        v = s.view()
        assert v.outcome == "formed"
        said[scenario] = v.banner
    assert "upside down" in said["Symmetric start that needs call"]
    assert "upside down" not in said["Heart from 10 robots"]
