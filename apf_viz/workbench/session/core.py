"""The session's core: the shared screen's fields, the run read-only, building a new run from a
configuration, and what a page with a given state is shown (the view model's view, made under the
run's lock). The commands build on it (workbench/session/*_commands.py)."""

from __future__ import annotations

from collections.abc import Callable, Hashable, Mapping, Sequence
from typing import Any, Generic, Self, TypeVar

from apf_viz.algorithms import DEFAULT_ALGORITHM, Factory
from apf_viz.core.engine import Engine
from apf_viz.core.formats import InputError, size_problem
from apf_viz.core.frames import random_y_up
from apf_viz.core.grid import Point, as_point
from apf_viz.core.schedulers import DEFAULT_SCHEDULER
from apf_viz.core.schedulers import REGISTRY as SCHEDULER_REGISTRY
from apf_viz.workbench.compare import Twin
from apf_viz.workbench.editor import Editor, draft_of
from apf_viz.workbench.lecturer import Lecturer
from apf_viz.workbench.library import PatternLibrary
from apf_viz.workbench.poll import Poll
from apf_viz.workbench.run_config import RunConfig
from apf_viz.workbench.run_controller import RunController
from apf_viz.workbench.screen_state import BrowserState, Mode, SharedScreen
from apf_viz.workbench.view_model import SessionView, browser_key, for_browser, present, present_run

T = TypeVar("T")
K = TypeVar("K", bound=Hashable)


def shape_key(cells: Sequence[Point]) -> tuple[Point, ...]:
    """A pattern's cells translated to min x = min y = 0, sorted: the same for the pattern wherever it is."""
    if not cells:
        return ()
    mx, my = min(x for x, _ in cells), min(y for _, y in cells)
    return tuple(sorted((x - mx, y - my) for x, y in cells))


SCHEDULER_LABELS = {kind.label: kind.name for kind in SCHEDULER_REGISTRY}
"""The UI's dropdown: each scheduler's label, and the name it stands for (core/schedulers)."""


class _ScreenField(Generic[T]):
    """A Session attribute that is the shared screen's field ``name`` (read and written), typed."""

    def __init__(self, name: str) -> None:
        self.name = name

    def __get__(self, session: Any, owner: type | None = None) -> T:
        if session is None:  # read on the class (introspection, docs): the descriptor itself
            return self  # type: ignore[return-value]
        value: T = getattr(session.screen, self.name)
        return value

    def __set__(self, session: Any, value: T) -> None:
        setattr(session.screen, self.name, value)


class SessionCore:
    """What every browser sees and drives: the run, the drafts, the mode and the selection; the
    commands are grouped by what they act on (:class:`~apf_viz.workbench.session.Session`)."""

    def __init__(
        self,
        robots: Sequence[Point],
        pattern: Sequence[Point],
        *,
        y_up: Sequence[bool] | None = None,
        algorithm: str = DEFAULT_ALGORITHM,
        scheduler: str = DEFAULT_SCHEDULER,
        seed: int = 1,
        light_semantics: str = "compute",
        max_events: int = 5_000_000,
        plugins: Mapping[str, Factory] | None = None,
    ) -> None:
        problem = size_problem(len(pattern), len(robots))
        if problem:
            raise InputError(problem)
        flips = tuple(y_up) if y_up is not None else tuple(random_y_up(len(robots), seed))
        config = RunConfig(
            tuple(map(as_point, robots)),
            flips,
            tuple(map(as_point, pattern)),
            algorithm,
            light_semantics,  # type: ignore[arg-type]
            scheduler,
            seed,
            max_events,
        )
        self._begin(config, plugins)

    @classmethod
    def from_config(cls, config: RunConfig, plugins: Mapping[str, Factory] | None = None) -> Self:
        """A session whose run is ``config`` as it is (another run's, copied: ui/own_runs.py)."""
        session = cls.__new__(cls)
        session._begin(config, plugins)
        return session

    def _begin(self, config: RunConfig, plugins: Mapping[str, Factory] | None) -> None:
        self.run = RunController(config, plugins)
        self.lock = self.run.lock
        self.screen = SharedScreen(Editor(config.robots, config.y_up, config.pattern))
        self.kept_drafts = False  # a load replaced drafts never run (:meth:`take_kept_drafts_note`)
        # The presenter's state: the selection the calls made without a page (scripts, tests) act on,
        # which the page presenting the run holds and the class pages may follow (workbench/classroom).
        self.presenter = BrowserState()
        self._new_run_listeners: list[Callable[[], None]] = []  # :meth:`on_new_run`
        self.lecturer: Lecturer | None = None  # a guided lecture being followed (PageDown: its next stop)
        # Each asked stop's answers, by (lecture, stop): a stop visited again keeps the room's answers.
        self.polls: dict[tuple[str, int], Poll] = {}
        self.library = PatternLibrary()  # saved patterns (serve --library chooses the folder)
        self.saved = self.library.names()  # their names, read once and after each save
        # A pattern's name, by its shape (:func:`shape_key`: where it is drawn does not matter, and the
        # drawing is moved beside the robots): the name it was saved or loaded under, for a download.
        self.pattern_names: dict[tuple[Point, ...], str] = {}

    def name_pattern(self, cells: Sequence[Point], name: str) -> None:
        """Remember ``name`` for the pattern of these cells, wherever it is drawn (a blank name is
        ignored)."""
        if name.strip():
            self.pattern_names[shape_key(cells)] = name.strip()

    def pattern_name(self, cells: Sequence[Point]) -> str | None:
        """The name the pattern of these cells was saved or loaded under, wherever it is drawn now."""
        return self.pattern_names.get(shape_key(cells))

    # ------------------------------------------------------------------ pages' selections
    def on_new_run(self, listener: Callable[[], None]) -> None:
        """Call ``listener`` (under the run's lock) whenever a new run makes every selection stale: the
        classroom clears its pages' selections (a robot of the old run is no robot of the new one)."""
        self._new_run_listeners.append(listener)

    def _clear_selections(self) -> None:
        self.presenter.selected = None
        for listener in self._new_run_listeners:
            listener()

    # ------------------------------------------------------------------ the screen, shared
    editor = _ScreenField[Editor]("editor")
    mode = _ScreenField[Mode]("mode")
    scenario_note = _ScreenField[str]("scenario_note")
    twin = _ScreenField[Twin | None]("twin")
    click_advances = _ScreenField[bool]("click_advances")
    numbers = _ScreenField[bool | None]("numbers")

    @property
    def selected(self) -> int | None:
        """The presenter's selected robot (scripts and tests select through it)."""
        return self.presenter.selected

    @selected.setter
    def selected(self, robot: int | None) -> None:
        """Select ``robot`` on the presenter's page (None: no robot)."""
        self.presenter.selected = robot

    # ------------------------------------------------------------------ the run, read-only
    @property
    def engine(self) -> Engine:
        """The run's engine, where the run stands now."""
        return self.run.engine

    @property
    def config(self) -> RunConfig:
        """How the run was configured: start, flips, pattern, algorithm, scheduler, seed."""
        return self.run.config

    @property
    def playing(self) -> bool:
        """Whether Play is on."""
        return self.run.playing

    @property
    def speed(self) -> float:
        """Steps per second while playing."""
        return self.run.speed

    @property
    def scheduler_name(self) -> str:
        """The scheduler's registry name (``async``, ``ssync``, …)."""
        return self.run.config.scheduler

    @property
    def seed(self) -> int:
        """The run's seed."""
        return self.run.config.seed

    @property
    def algorithm_name(self) -> str:
        """The algorithm's registry name."""
        return self.run.config.algorithm

    @property
    def robots(self) -> list[Point]:
        """The run's start, global frame."""
        return list(self.run.config.robots)

    @property
    def pattern(self) -> list[Point]:
        """The run's pattern."""
        return list(self.run.config.pattern)

    @property
    def y_up(self) -> list[bool]:
        """The robots' flips: whether each one's +y is the global +y."""
        return list(self.run.config.y_up)

    # ------------------------------------------------------------------ what to show
    def view(self, state: BrowserState | None = None) -> SessionView:
        """What a page with that state shows (the presenter's view for None)."""
        with self.lock:
            return present(self.run, self.screen, state or self.presenter, self.presenter)

    def views(self, pages: Mapping[K, BrowserState]) -> tuple[SessionView, dict[K, SessionView]]:
        """The run's view (what every page shares) and each page's, made at one instant: the run's part
        once, each page's selection laid over it."""
        with self.lock:
            shared = present_run(self.run, self.screen)
            made: dict[tuple[Any, ...], SessionView] = {}  # one view per browser_key: a class shares a few
            own = {}
            for b, state in pages.items():
                key = browser_key(state, self.presenter)
                if key not in made:
                    made[key] = for_browser(shared, self.run, self.screen, state, self.presenter)
                own[b] = made[key]
            return shared, own

    def compare_with(self, algorithm: str | None) -> None:
        """Compare: draw the same run (start, pattern, flips, adversary) under ``algorithm`` beside it,
        stepping with it; None stops comparing."""
        with self.lock:
            self.screen.twin = Twin(algorithm, self.run.plugins) if algorithm else None

    def branch_here(self) -> None:
        """Stop following a loaded trace: from this event on, the chosen scheduler runs."""
        self.run.branch_here()

    def return_to_set_aside(self, number: int | None = None) -> None:
        """Enter a kept branch (the newest by default); Step then follows it. The line left is kept."""
        self.run.return_to_set_aside(number)

    def back_cycle(self) -> str:
        """Back over the last actor's whole Look-Compute-Move cycle."""
        with self.lock:
            return self.run.back_cycle()

    # ------------------------------------------------------------------ building runs
    def _start(self, config: RunConfig) -> None:
        """A new run from ``config``; the drafts follow it and the selection is cleared."""
        self._drafts_follow(config)
        self.run.restart(config)
        self._clear_selections()
        self.mode = "run"
        self.scenario_note = ""  # what a Demo scenario shows no longer applies

    def _drafts_follow(self, config: RunConfig) -> None:
        """The drafts become ``config``'s start and pattern, the old ones kept for Undo; drafts that the
        run did not have (drawn, not yet run) are noted in :attr:`kept_drafts` for the browser to be
        told."""
        e, now = self.editor, self.run.config
        unrun = e.draft != draft_of(now.robots, now.y_up, now.pattern)
        # No change when the run starts from the drafts themselves (Mode back to Run).
        if e.start_from(config.robots, config.y_up, config.pattern):
            self.kept_drafts = self.kept_drafts or unrun

    def take_kept_drafts_note(self) -> str | None:
        """Once, after a load replaced drafts that had not been run: how to get them back."""
        kept, self.kept_drafts = self.kept_drafts, False
        if not kept:
            return None
        return "what you drew in Edit is kept: in the Edit folder, Undo brings it back"
