"""The stages a lecture stops at (issue #23): Next stage stops at the paper's sub-stages, and the
timeline marks where each began."""

from __future__ import annotations

from apf_viz.algorithms.apf_opaque_grid.portrayal import stage
from apf_viz.ui.app import demo_session
from apf_viz.workbench.stage_log import MOVES_READ_UP_TO_K, StageLog, headline

FOREVER = float("inf")  # no time budget: these tests assert what happens, not how fast


def _played():
    s = demo_session()
    seen: list[tuple[int, str]] = [(0, s.view().stage)]
    while not s.engine.finished:
        s.step()
        now = s.view().stage
        if now != seen[-1][1]:
            seen.append((s.engine.step_index, now))
    return s, seen


def test_the_demo_passes_every_sub_stage_of_the_paper_in_order():
    _, seen = _played()
    details = [st.split(" — ")[1] if " — " in st else st for _, st in seen]
    expected_in_order = [
        "every robot off",
        "L_1's terminal robots light terminal1",
        "one terminal robot lights symmetric; its partner has not yet",  # the second: a few events later
        "L_1's terminal pair is symmetric about K",
        "a robot lights decider; its partner has not yet",
        "two deciders stand on L_1",
        "leader elected (leader1), walking to its corner",
        *[f"the leader at its corner; {i} of 9 robots lined up on its row" for i in range(10)],
        "the line is complete; its left end leaves for the first target",
        *[f"{i} of 9 robots on their targets" for i in range(1, 9)],
        "the leader walks to the last target",
        "Formed: every robot is done",
    ]
    assert details == expected_in_order


def test_the_timeline_marks_every_stage_where_it_began_and_labels_each_phase_once():
    s, seen = _played()
    marks = s.run.stages.marks(s.engine.history, s.engine.history.length)
    assert [at for at, _ in marks] == [at for at, _ in seen[1:]]
    # Phase 2 begins at step 27 and Phase 3 at 60 of 542: their labels would print over each other on
    # the slider, so Phase 2's mark stays unlabelled.
    assert [label for _, label in marks if label] == ["Phase 3", "Formed"]
    assert (27, None) in marks and (60, "Phase 3") in marks
    assert s.view().timeline_marks == marks  # the view carries them to the slider


def test_next_stage_stops_exactly_at_each_mark():
    s, seen = _played()
    s.reset()
    stops = []
    while not s.engine.finished:
        s.run_until("stage", seconds=FOREVER)
        stops.append(s.engine.step_index)
    assert stops == [at for at, _ in seen[1:]]


def test_a_branch_rewrites_the_marks_after_it():
    s, _ = _played()
    log = s.run.stages
    before = log.marks(s.engine.history, s.engine.history.length)
    s.seek(40)
    recorded = s.engine.history.steps[40].record.robots
    s.run.step_robot(next(r for r in range(s.engine.k) if (r,) != tuple(recorded)))  # drops the future
    after = log.marks(s.engine.history, s.engine.history.length)
    assert [at for at, _ in after if at <= 40] == [at for at, _ in before if at <= 40]
    assert s.engine.history.length == 41 and all(at <= 41 for at, _ in after)


def test_with_many_robots_only_light_changes_are_read():
    k = MOVES_READ_UP_TO_K + 1
    calls = []

    def stage_of(pts, lights):
        calls.append(1)
        return "lit" if "on" in lights else "dark"

    class Step:
        def __init__(self, events):
            self.events = events

    class History:
        generation = 0

        def __init__(self, steps):
            self.steps = steps
            self.length = len(steps)

        def effects(self, start, stop):
            for s in self.steps[start:stop]:
                yield tuple(Effect(e.robot, e.phase, e.light, e.to, e.collision) for e in s.events)

    from apf_viz.core.history import Effect, Event

    move = Step([Event(0, "move", to=(5, 5))])
    light = Step([Event(1, "compute", light="on")])
    log = StageLog([(i, 0) for i in range(k)], ["off"] * k, stage_of)
    assert log.changes(History([move, move, light]), 3) == [(0, "dark"), (3, "lit")]
    assert len(calls) == 2  # the start, and the light change: the moves were not read


def test_headline_is_the_text_before_the_dash():
    assert headline(stage(((0, 0), (1, 0)), ("leader", "done"))) == "Phase 3: pattern formation (Algorithm 3)"
