"""The view model: turns the run (engine, history, config), the shared screen and *one browser's* state
into the :class:`SessionView` that browser's scene and panels draw, sentences included. Pure: no viser,
no locks (the session holds its lock while calling), no particular algorithm (what is drawn over the run
and why a robot acted come from the algorithm's own description, core/portrayal.py).

The run's part is the same for every browser and is made once a frame (:func:`present_run`); each
browser's part (its selection: rays, ghosts, the caption, Why) is laid over it (:func:`for_browser`)."""

from __future__ import annotations

from dataclasses import replace
from itertools import repeat
from typing import Any

import numpy as np

from apf_viz.core.budget import paper_D
from apf_viz.core.engine import NEXT_EVENT, Engine
from apf_viz.core.engine_state import Phase
from apf_viz.core.frames import move_to_global
from apf_viz.core.grid import Point
from apf_viz.core.pattern_match import matches_only_mirrored
from apf_viz.core.portrayal import (
    Cells,
    Configuration,
    Overlays,
    legend_of,
    overlays_of,
    title_of,
)
from apf_viz.core.portrayal import stage_of as algorithm_stage
from apf_viz.core.schedulers import BY_HAND
from apf_viz.workbench.screen_state import NUMBERS_UP_TO, BrowserState, LectureStop, SharedScreen
from apf_viz.workbench.view_model import story
from apf_viz.workbench.view_model.paper import paper_html_for
from apf_viz.workbench.view_model.run_source import RunSource
from apf_viz.workbench.view_model.staleness import hidden_from, seen_robots, stale_holders
from apf_viz.workbench.view_model.views import Ghost, RobotView, SessionView, WhyView
from apf_viz.workbench.view_model.why import why_markdown, why_view

__all__ = ["RobotView", "SessionView", "WhyView", "for_browser", "present", "present_run"]

_PHASE_NAMES = ("idle", "looked", "computed")  # indexed by Phase
# Up to this many robots the screen marks every robot holding a stale snapshot, and greys the robots the
# selected one cannot see: each costs a walk of the history since each holder's Look (or O(k) per frame);
# a crowd is read through the selected robot's caption instead.
SIGHT_MARKS_UP_TO = 60
_COMPUTED = int(Phase.COMPUTED)


def present(
    run: RunSource, screen: SharedScreen, browser: BrowserState, presenter: BrowserState
) -> SessionView:
    """The whole view of one browser (``presenter``: whose selection a following browser shows)."""
    return for_browser(present_run(run, screen), run, screen, browser, presenter)


def present_run(run: RunSource, screen: SharedScreen) -> SessionView:
    """What every browser shows alike: the run, its story and the shared screen; nothing selected."""
    e = run.engine
    st = e.state
    pts = e.current_points()
    running = screen.mode == "run"
    # In either Edit mode the robots drawn are the drafted ones, the robots the header counts.
    robots = robot_views(e, pts) if running else _drafted_robots(e, screen)
    overlays = _overlays(run, screen, pts, st.lights)
    numbers = run_numbers(e, overlays)
    crash = story.collision(e, pts) if st.outcome == "collision" and running else None
    stuck = st.outcome == "stuck" and running
    view = SessionView(
        robots=tuple(robots),
        targets=_targets(overlays),
        overlays=overlays,
        legend=legend_of(e.algorithm),
        outcome=st.outcome,
        caption=story.caption(e, None, True, []),
        last_events=story.last_events(e),
        note_here=run.note_here(),
        trace_position=run.trace_position,
        # Formed, nothing is pending any more: rings of phase and of the last actor would read as marks.
        last_actor=story.last_actor(e) if running and st.outcome != "formed" else None,
        phase_rings=st.outcome != "formed",
        numbers=screen.numbers if screen.numbers is not None else len(robots) <= NUMBERS_UP_TO,
        collision=crash[:2] if crash else None,
        collided=crash[2] if crash else (),
        fatal=story.fatal_decisions(e, crash[2], pts) if crash else ("", None),
        waits=story.wait_for(e) if stuck else "",
        never_act=tuple(range(e.k)) if stuck else (),
        algorithm=run.config.algorithm,
        algorithm_title=title_of(e.algorithm),
        branches=run.branches.labels(),
        following_what=run.following_what,
        compare=_twin_view(run, screen) if screen.twin is not None and running else None,
        divergence=(split := screen.twin.divergence(e) if screen.twin is not None and running else None),
        diverged=split.robot if split is not None else None,
        trace_note=story.trace_note(run.trace_options),
        **_over_time(run, screen, pts) if running else {"trail_setting": screen.trails},
        **numbers,
        **_screen_fields(run, screen),
        move_series=run.series.at(e.history, e.step_index),
        scheduler=run.config.scheduler,
        playing=run.playing,
        why_text=why_markdown(None),
        paper_decision=story.last_decision(e),
    )
    return _told(view, run, crash[0] if crash else None, stuck)


def _screen_fields(run: RunSource, screen: SharedScreen) -> dict[str, Any]:
    """What the shared screen adds to the run's view: the mode and its drafts, a scenario's note, a
    lecture's caption."""
    editing = screen.mode != "run"
    return {
        "mode": screen.mode,
        "draft_count": len(screen.editor.pattern),  # the pattern drawn (Edit), or the run's
        "robot_count": len(screen.editor.robots) if editing else run.engine.k,
        "axis": screen.editor.axis() if screen.mode == "edit-robots" else None,
        "anchor": screen.studio.anchor if editing else None,
        "fit_preview": screen.studio.fit_preview(screen.editor) if editing else "",
        "selection_box": _selection_box(screen) if editing else None,
        "mirror_axes": screen.studio.axes if editing else (None, None),
        "click_advances": screen.click_advances,
        "scenario_note": screen.scenario_note,
        "lecture": lecture_words(screen.lecture, run.engine, run.playing),
        "lecture_title": screen.lecture.lecture if screen.lecture is not None else "",
        "poll": screen.poll.view(screen.seats_here) if screen.poll is not None else None,
    }


def _told(view: SessionView, run: RunSource, crash: str | None, stuck: bool) -> SessionView:
    """The run's view with what is said of it: the Paper panel, the divergence marked in both runs of
    Compare, a followed trace's end, and the panels' sentences."""
    e = run.engine
    view = replace(view, paper_text=paper_html_for(e.algorithm, view.paper_decision, view.algorithm))
    if view.compare is not None and view.diverged is not None:  # marked in both runs
        view = replace(view, compare=replace(view.compare, diverged=view.diverged))
    position = run.trace_position
    at_end = position is not None and position[0] >= position[1]
    if at_end and _walks(run):
        view = replace(view, endless=story.endless_words(run.trace_options))
    mirrored = view.outcome == "formed" and matches_only_mirrored(e.current_points(), run.config.pattern)
    return replace(view, **_sentences(view, crash, stuck, mirrored))


def _selection_box(screen: SharedScreen) -> tuple[Point, Point] | None:
    """The selection's outline, while a cell it took is still in the draft being edited."""
    editor = screen.editor
    drawn = editor.robots if screen.mode == "edit-robots" else editor.pattern
    return screen.studio.selection.box_over(drawn)


def lecture_words(stop: LectureStop | None, engine: Engine, playing: bool) -> tuple[str, str, str] | None:
    """A lecture's caption: (where, title, words). The stop's words hold at the state it was reached; once
    the run is played or stepped off it, they would describe another moment: the caption then says so,
    where the run stands, and where PageDown and PageUp go."""
    if stop is None:
        return None
    where = f"stop {stop.index + 1} of {stop.count} · {stop.lecture}"
    if stop.mark is not None and stop.mark.holds(engine) and not playing:
        return where, stop.title, stop.say
    event = engine.state.events
    back = stop.mark is not None and engine.step_index < stop.mark.step
    how = "playing on" if playing else ("stepped back" if back else "played on")
    ahead = (
        f"PageDown: stop {stop.index + 2}, “{stop.next_title}”."
        if stop.next_title
        else "That was the last stop."
    )
    return (
        f"away from stop {stop.index + 1} of {stop.count} · {stop.lecture}",  # not "off": a light
        f"{how.capitalize()} from stop {stop.index + 1} — event {event}",
        f"The words of stop {stop.index + 1}, “{stop.title}”, were about event {stop.event}. {ahead} "
        f"PageUp: back to stop {stop.index + 1}.",
    )


def _over_time(run: RunSource, screen: SharedScreen, pts: list[Point]) -> dict[str, Any]:
    """What the run's history adds to its picture: trails, the stale marks, the timeline's marks."""
    e = run.engine
    stale = stale_holders(e, pts) if e.k <= SIGHT_MARKS_UP_TO else []
    length = e.history.length
    marks = run.stages.marks(e.history, length) + story.loop_marks(
        run.trace_options, length, run.config.scheduler
    )
    return {
        "trails": story.trails(e, _trail_moves(run, screen), pts),
        "trail_setting": screen.trails,
        "stale_holders": tuple(stale),
        "timeline_marks": tuple(sorted(marks, key=lambda mark: mark[0])),
    }


def _trail_moves(run: RunSource, screen: SharedScreen) -> int:
    """The moves of each robot's trail: the person's choice; a trace of a walk that never ends (a
    livelock, an escape) shows its walkers' paths in any case."""
    return max(screen.trails, story.LOOP_TRAIL if _walks(run) else 0)


def _walks(run: RunSource) -> bool:
    """The run follows a trace of a walk that never ends."""
    return run.following and run.trace_options.get("verdict") in story.ENDLESS


def _sentences(view: SessionView, crash: str | None, stuck: bool, mirrored: bool = False) -> dict[str, Any]:
    """The panels' sentences about the run, from the facts of its view."""
    why = view.fatal[0] or view.waits
    out = {
        "banner": story.banner(view.outcome, crash, stuck, why, view.endless, mirrored)
        if view.mode == "run"
        else "",
        "stats": story.stats(view.algorithm, view.__dict__),
        "counts": story.counts(view.mode, view.draft_count, view.robot_count, len(view.robots), view.axis),
        "trace_line": story.trace_line(view.trace_position, view.following_what, view.trace_note),
        "aside_line": story.aside_line(view.branches),
    }
    twin = view.compare
    if twin is not None:
        a = (view.algorithm, view.outcome, view.event, view.moves)
        b = (twin.algorithm, twin.outcome, twin.event, twin.moves)
        out["compare_text"] = story.compare_text(a, b, view.divergence)
    if view.scheduler in BY_HAND:
        out["next_phases"] = story.next_phases([r.next_event for r in view.robots], view.click_advances)
    return out


def browser_key(browser: BrowserState, presenter: BrowserState) -> tuple[int | None, bool]:
    """What :func:`for_browser` depends on of a browser: the robot whose selection it shows, and whether
    it shows the presenter's. Browsers with one key are shown one view (a class following the lecture,
    or pages that selected the same robot): made once."""
    source = presenter if browser.follow and browser is not presenter else browser
    return source.selected, source is presenter and browser is not presenter


def for_browser(
    view: SessionView,
    run: RunSource,
    screen: SharedScreen,
    browser: BrowserState,
    presenter: BrowserState,
) -> SessionView:
    """``view`` (the run's) with this browser's selection: rays, ghosts, the caption and Why."""
    e = run.engine
    source = presenter if browser.follow and browser is not presenter else browser
    sel = source.selected
    if sel is None or sel >= e.k or screen.mode != "run":
        return replace(view, follows_presenter=source is presenter and browser is not presenter)
    st = e.state
    pts = [r.position for r in view.robots]  # the run's robots as they are now (Run mode)
    seen = seen_robots(e, sel, "held", pts) if st.snapshot[sel] is not None else []
    if st.snapshot[sel] is not None:  # what it saw, not what is there now
        rays = tuple((pts[sel], s.seen_at) for s in seen)
        ghosts = tuple(
            Ghost(s.seen_at, s.seen_light, s.robot, s.seen_at == s.now_at) for s in seen if s.changed
        )
    else:
        rays, ghosts = tuple((pts[sel], pts[j]) for j in e.visible(sel).tolist()), ()
    hidden = hidden_from(e, sel, pts) if e.k <= SIGHT_MARKS_UP_TO else {}
    why = why_view(e, sel, pts)
    decided = why.explanation.decision.rule_id if why.explanation is not None else ""
    paper: dict[str, Any] = (
        {
            "paper_decision": (sel, decided),
            "paper_text": paper_html_for(e.algorithm, (sel, decided), view.algorithm),
        }
        if decided
        else {}
    )
    return replace(
        view,
        **paper,
        selected=sel,
        rays=rays,
        ghosts=ghosts,
        hidden=tuple(sorted(hidden)),
        hiders=tuple(sorted((hider, j) for j, hider in hidden.items())),
        why=why,
        why_text=why_markdown(why),
        caption=story.caption(e, sel, e.y_up[sel], seen),
        stale=tuple(s.robot for s in seen if s.changed),
        follows_presenter=source is presenter and browser is not presenter,
    )


def robot_views(e: Engine, pts: list[Point]) -> list[RobotView]:
    """What the scene draws for each robot of engine ``e`` (``pts``: its current points)."""
    st = e.state
    phases = st.phase.tolist()
    pending: list[Point | None] = [None] * e.k
    for r in np.flatnonzero(st.phase == _COMPUTED).tolist():
        decision = st.pending[r]
        if decision is not None and decision.move is not None:
            dx, dy = move_to_global(decision.move, e.y_up[r]).delta
            pending[r] = (pts[r][0] + dx, pts[r][1] + dy)
    # tuple.__new__ mapped in C: a thousand robots a frame, and a NamedTuple's __new__ is Python.
    return list(
        map(
            tuple.__new__,
            repeat(RobotView),
            zip(
                pts,
                st.lights,
                [_PHASE_NAMES[p] for p in phases],
                e.y_up,
                pending,
                [NEXT_EVENT[p] for p in phases],
                strict=True,
            ),
        )
    )


def run_numbers(e: Engine, overlays: Overlays) -> dict[str, Any]:
    """The counts and stage a panel shows for engine ``e`` (the run's, or Compare's second run)."""
    st = e.state
    return {
        "event": st.events,
        "steps": st.steps,
        "history_length": e.history.length,
        "moves": st.moves,
        "cycles": st.cycles,
        "stage": overlays.stage,
        "lights_in_use": tuple(sorted(set(st.lights), key=e.algorithm.lights.index)),
        "skipped": st.skipped,
        "moves_per_kD": st.moves / (e.k * paper_D(e.start, e.pattern)),
    }


def stage_of(run: RunSource, screen: SharedScreen) -> str:
    """The algorithm's stage now (Next stage and a lecture's stops ask after every step): in Run by the
    algorithm's own stage name, which draws no marks (core/portrayal.py ``stage_of``)."""
    e = run.engine
    if screen.mode != "run":
        return _overlays(run, screen, e.current_points(), e.state.lights).stage
    return algorithm_stage(e.algorithm, _configuration(run, e.current_points(), e.state.lights))


def _configuration(run: RunSource, pts: list[Point], lights: list[str]) -> Configuration:
    """The run at one moment as the algorithm's portrayal reads it (global frame, for the screen only)."""
    return Configuration(tuple(pts), tuple(lights), run.config.pattern, run.config.robots)


def _drafted_robots(e: Engine, screen: SharedScreen) -> list[RobotView]:
    """Edit robots or pattern: the robots being placed (the drafts), not the run's."""
    first = e.algorithm.lights[0]
    editor = screen.editor
    return [
        RobotView(p, first, "idle", up, None, "look")
        for p, up in zip(editor.robots, editor.y_up, strict=True)
    ]


def _targets(overlays: Overlays) -> tuple[Point, ...]:
    return next((m.points for m in overlays.marks if isinstance(m, Cells)), ())


def _overlays(run: RunSource, screen: SharedScreen, pts: list[Point], lights: list[str]) -> Overlays:
    """The algorithm's marks over the run; while a pattern is drawn, that pattern's cells instead, and
    while robots are placed, the pattern they will be given (the draft's, not the run's)."""
    if screen.mode == "edit-pattern":
        drawn = Cells(
            tuple(screen.editor.pattern), "pattern being drawn", "drawing"
        )  # the legend's swatch too
        return Overlays((drawn,), "editing the pattern")
    if screen.mode == "edit-robots":
        return Overlays(
            (Cells(tuple(screen.editor.pattern), "pattern for these robots", "preview"),),
            "editing the robots",
        )
    return overlays_of(run.engine.algorithm, _configuration(run, pts, lights))


def _twin_view(run: RunSource, screen: SharedScreen) -> SessionView:
    """Compare's second run as the scene draws it: robots, the algorithm's overlays, its outcome."""
    assert screen.twin is not None
    t = screen.twin.follow(run.engine, run.config)
    pts = t.current_points()
    st = t.state
    overlays = overlays_of(t.algorithm, Configuration(tuple(pts), tuple(st.lights), t.pattern, t.start))
    return SessionView(
        robots=tuple(robot_views(t, pts)),
        targets=_targets(overlays),
        overlays=overlays,
        legend=legend_of(t.algorithm),
        outcome=st.outcome,
        **run_numbers(t, overlays),
        mode="run",
        draft_count=len(t.pattern),
        robot_count=t.k,
        axis=None,
        numbers=screen.numbers if screen.numbers is not None else t.k <= NUMBERS_UP_TO,
        collision=None,
        never_act=tuple(range(t.k)) if st.outcome == "stuck" else (),
        algorithm=screen.twin.algorithm,
        algorithm_title=title_of(t.algorithm),
    )
