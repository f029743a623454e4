"""What the screen shows, as plain data: the scene draws a :class:`SessionView` and the panels put its
sentences in place. Built by :func:`apf_viz.workbench.view_model.present`."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple

from apf_viz.core.algorithm import Decision
from apf_viz.core.grid import Point
from apf_viz.core.portrayal import Explanation, LightStyle, Mark, Overlays
from apf_viz.core.schedulers import DEFAULT_SCHEDULER
from apf_viz.workbench.compare import Divergence
from apf_viz.workbench.poll import PollView
from apf_viz.workbench.screen_state import Mode


class RobotView(NamedTuple):
    """What the scene draws for one robot (a named tuple: a frame builds a thousand of them)."""

    position: Point
    light: str
    phase: str  # idle / looked / computed
    y_up: bool
    pending: Point | None  # global target of a computed move
    next_event: str


class Ghost(NamedTuple):
    """Where the selected robot saw ``robot``, in the light it saw; ``light_only`` when it has not moved
    since (only its light changed: the ghost stands on the robot itself)."""

    at: Point
    light: str
    robot: int
    light_only: bool = False


@dataclass(frozen=True)
class WhyView:
    """The selected robot's last decision and its evidence; regions already in the global frame."""

    robot: int
    explanation: Explanation | None  # None: the robot has not decided yet
    origin: Point  # where the robot stood when it looked (its frame's origin)
    regions: tuple[Mark, ...]
    holds_snapshot: bool  # it has looked again since (its next Compute will decide anew)
    changed: tuple[str, ...] = ()  # robots its decision saw that have since moved or changed light
    now: Decision | None = None  # what it would decide if it looked now
    changed_robots: tuple[int, ...] = ()  # the robot numbers of ``changed``


@dataclass(frozen=True)
class SessionView:
    """Everything the scene and panels show, computed in one place from the engine's state."""

    robots: tuple[RobotView, ...]
    targets: tuple[Point, ...]  # the cells of the overlays (or of the pattern being drawn)
    overlays: Overlays
    legend: dict[str, LightStyle]
    outcome: str | None
    event: int
    steps: int
    history_length: int
    moves: int
    cycles: int
    stage: str
    lights_in_use: tuple[str, ...]
    moves_per_kD: float
    mode: Mode
    draft_count: int  # points of the pattern being drawn (in Run: the pattern)
    robot_count: int  # robots being placed (in Run: the run's)
    axis: float | None  # the unsolvable symmetry axis of the robots being edited, if any
    anchor: Point | None = None  # Edit: the first click of a two-click tool (line, outline, move)
    fit_preview: str = ""  # Edit: what Fit pattern and Fit robots would do now
    selection_box: tuple[Point, Point] | None = None  # Edit: the corners of the studio's selection
    mirror_axes: tuple[float | None, float | None] = (None, None)  # Edit: the live mirror's x and y axes
    selected: int | None = None  # this browser's (or, following, the presenter's) selected robot
    rays: tuple[tuple[Point, Point], ...] = ()  # to what the selected robot saw (its snapshot) or sees now
    ghosts: tuple[Ghost, ...] = ()  # where a robot was seen, in the light seen, if changed since
    hidden: tuple[int, ...] = ()  # robots the selected robot does not see (its snapshot's, or now)
    hiders: tuple[tuple[int, int], ...] = ()  # (hider, hidden): the robot between that hides each one
    trails: tuple[tuple[Point, ...], ...] = ()  # each robot's recent path, oldest first (empty: none)
    trail_setting: int = 0  # the Trails slider: moves per trail the person chose
    stale_holders: tuple[int, ...] = ()  # every robot holding a snapshot that shows others as they were
    why: WhyView | None = None
    caption: str = ""
    move_series: tuple[tuple[int, int], ...] = field(default=())
    skipped: int = 0  # robot·steps passed over because their next cycle could change nothing
    last_events: tuple[str, ...] = ()  # newest first, in words
    last_actor: int | None = None  # the robot of the last step (one robot: ASYNC or Manual)
    numbers: bool = False  # draw each robot's number beside it
    trace_position: tuple[int, int] | None = None  # (event, events in the trace) while following one
    collision: tuple[str, tuple[Point, ...]] | None = None  # what collided, in words, and the cells
    collided: tuple[int, ...] = ()  # the robots of the collision (the facts of its sentence)
    never_act: tuple[int, ...] = ()  # stuck: robots whose every future cycle changes nothing
    scenario_note: str = ""  # what the Demo scenario shown shows
    algorithm: str = ""  # the run's algorithm (by name)
    algorithm_title: str = ""  # the run's algorithm in words (Compare's titles, the caption)
    note_here: str = ""  # what a followed schedule's line says of the step just taken
    branches: tuple[str, ...] = ()  # the lines of steps branches dropped, oldest first, as listed
    following_what: str = "the trace"  # what Step follows while trace_position is set
    click_advances: bool = True  # Manual: a click on a robot runs its next phase (else: selects only)
    compare: SessionView | None = None  # Compare: the same adversary under the second algorithm
    divergence: Divergence | None = None  # Compare: the first event where the two differ, its robot
    diverged: int | None = None  # Compare: the robot of that event, marked in both runs
    trace_note: str = ""  # what a loaded trace's header says it shows (a verdict, a gap, a loop)
    # Steps of the timeline worth a mark: where each stage began (labelled where the phase changes), a loop.
    timeline_marks: tuple[tuple[int, str | None], ...] = ()
    stale: tuple[int, ...] = ()  # robots the selected robot's held snapshot shows other than they are now
    scheduler: str = DEFAULT_SCHEDULER  # the run's scheduler (by name)
    playing: bool = False
    # The sentences of the panels, made here so that a test can read them without a browser.
    banner: str = ""  # the outcome, located
    stats: str = ""  # algorithm, moves, cycles, stage, lights
    compare_text: str = ""  # Compare: each side's state and the first divergence
    counts: str = ""  # Edit: targets or robots drawn
    next_phases: str = ""  # Manual: who is next for what
    why_text: str = ""  # the Why panel
    # The Paper panel: the decision whose line it highlights — (robot, rule id): the selected robot's last,
    # else the run's last Compute — and the panel's HTML.
    paper_decision: tuple[int, str] | None = None
    paper_text: str = ""
    lecture: tuple[str, str, str] | None = None  # a guided lecture's stop: (where, title, words)
    lecture_title: str = ""  # the guided lecture being followed ("": none)
    poll: PollView | None = None  # the stop's question to the room: how many answered, the spread
    trace_line: str = ""  # following a trace or schedule: where, and what its header says
    aside_line: str = ""  # a branch set recorded steps aside
    follows_presenter: bool = False  # this browser shows the presenter's selection
    # A collision explained: each mover's fatal decision (when, on what, what changed since), in words,
    # and the step of the earliest such Compute (Go to the fatal decision).
    fatal: tuple[str, int | None] = ("", None)
    waits: str = ""  # a deadlock: what each robot waits on (its rule now), robots grouped by rule
    # A livelock's or an escape's trace played to its end: (its verdict, in words); the engine sees a run
    # still going, so there is no outcome.
    endless: tuple[str, str] | None = None
    phase_rings: bool = True  # draw the looked / computed rings (not once the pattern is formed)

    @property
    def stage_line(self) -> str:
        """The caption's stage line: the outcome once there is one (a stuck or collided run is no longer
        in the phase it was in), a walk that never ends at its trace's end, else the algorithm's stage."""
        if self.outcome == "collision":
            return "COLLISION: two robots on one cell"
        if self.outcome == "stuck":
            return "STUCK: no robot will act again"
        if self.outcome == "limit":
            return "LIMIT: stopped at its event budget, not formed"
        if self.endless is not None:
            return f"{self.endless[0]}: it never ends"
        return self.stage
