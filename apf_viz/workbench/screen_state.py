"""The state of the screen apart from the run: what every browser shares (the mode, the drafts, the
numbers, a Demo note, Compare) and what each browser has of its own (its selection, whether it follows
the presenter's, its camera). :class:`~apf_viz.workbench.session.Session` changes them; the view model
(workbench/view_model) reads them."""

from __future__ import annotations

import weakref
from dataclasses import dataclass, field
from typing import Literal

from apf_viz.core.engine import Engine
from apf_viz.workbench.compare import Twin
from apf_viz.workbench.editor import Editor
from apf_viz.workbench.poll import Poll
from apf_viz.workbench.studio import Studio

Mode = Literal["run", "edit-pattern", "edit-robots"]
# A page's role (workbench/classroom/roles.py tells which a page is): a presenter drives the shared run;
# a class page follows.
Role = Literal["presenter", "class"]
NUMBERS_UP_TO = 50  # robots: numbers are on by default up to this many (beyond, they hide the run)


@dataclass
class SharedScreen:
    """What every browser shows alike, besides the run itself."""

    editor: Editor
    mode: Mode = "run"
    numbers: bool | None = None  # robot numbers on the canvas; None: on up to NUMBERS_UP_TO robots
    click_advances: bool = True  # Manual: a click runs the robot's next phase; False: it only selects
    scenario_note: str = ""  # what the Demo scenario being shown shows, until another run starts
    twin: Twin | None = None  # Compare: a second algorithm stepping with the run
    trails: int = 0  # draw each robot's last this-many moves (0: none)
    studio: Studio = field(default_factory=Studio)  # Edit: the tool, its size and text, a gesture begun
    lecture: LectureStop | None = None  # a guided lecture's stop, as it was reached
    poll: Poll | None = None  # its question to the room, and the room's answers
    seats_here: frozenset[str] = frozenset()  # the class pages' seats connected now (ui/app.py says)


@dataclass(frozen=True)
class RunMark:
    """Where a run stood: its engine (held weakly: a new engine may reuse a dropped one's id()), its
    history's generation (a branch that drops steps bumps it) and the step it was at."""

    run: weakref.ref[Engine] = field(compare=False, repr=False)
    generation: int
    step: int

    @classmethod
    def of(cls, engine: Engine) -> RunMark:
        """Where ``engine`` stands now."""
        return cls(weakref.ref(engine), engine.history.generation, engine.step_index)

    def on_history(self, engine: Engine) -> bool:
        """The same engine, along the same history, which still holds the step marked."""
        return (
            self.run() is engine
            and engine.history.generation == self.generation
            and (engine.history.length >= self.step)
        )

    def holds(self, engine: Engine) -> bool:
        """The run stands exactly where it was marked."""
        return self.on_history(engine) and engine.step_index == self.step


@dataclass(frozen=True)
class LectureStop:
    """A guided lecture's stop as it was reached: its words hold at that state only (:attr:`mark`); once
    the run is played or stepped off it, the screen says where the run is instead."""

    lecture: str  # the lecture's title
    index: int  # 0-based
    count: int  # stops in the lecture
    title: str
    say: str
    event: int  # the event at which the stop was reached
    next_title: str | None = None  # the next stop's title (None: the last stop)
    mark: RunMark | None = None  # where the stop left the run
    class_address: bool = False  # the presenter's page shows the class address while at this stop


@dataclass
class BrowserState:
    """One browser's own part of the screen. A laptop selecting a robot does not change what the
    projector shows, unless the projector chose to ``follow`` the presenter's selection."""

    selected: int | None = None
    follow: bool = False  # show the presenter's selection instead of one's own
    role: Role = "presenter"  # a class page follows the lecture; it drives only when the class may
    # The camera: "framed" (kept on the whole run as it grows) or "moved" by hand (left where it is
    # until a new run starts or Frame run is pressed); and the box and run it was last framed on.
    camera: Literal["framed", "moved"] = "framed"
    framed_bounds: tuple[float, float, float, float] | None = None
    framed_run: object | None = field(default=None, repr=False)
