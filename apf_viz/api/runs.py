"""One run from Python: :func:`run` drives the same engine, budget and scheduler as ``apf-viz run``, and
returns a :class:`Run` to read, tabulate, draw, show in a notebook and save."""

from __future__ import annotations

import html
import os
import warnings
from collections.abc import Mapping
from dataclasses import asdict
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal

from apf_viz.algorithms import DEFAULT_ALGORITHM, Factory, algorithm_from_command_line
from apf_viz.api.inputs import Points, Start, start_of, whole_number
from apf_viz.api.progress_bars import ProgressBar
from apf_viz.api.tables import pandas_for
from apf_viz.core.algorithm import Algorithm
from apf_viz.core.budget import run_budget
from apf_viz.core.engine import Engine, LightSemantics
from apf_viz.core.files import check_readable, check_writable, write_atomic
from apf_viz.core.formats import InputError, trace_text
from apf_viz.core.grid import Point
from apf_viz.core.run import RunSummary, advance, trace_header
from apf_viz.core.schedule import (
    Schedule,
    adversary_flips,
    check_robots,
    follow,
    load_schedule,
    schedule_of_steps,
    schedule_text,
)
from apf_viz.core.schedulers import AUTOMATIC, DEFAULT_SCHEDULER, make_scheduler
from apf_viz.core.symmetry import unsolvable_start

if TYPE_CHECKING:
    import pandas

    from apf_viz.workbench.session import Session


def run(
    robots: Points,
    pattern: Points,
    *,
    scheduler: str | None = None,
    seed: int = 1,
    algorithm: str | None = None,
    light_semantics: LightSemantics | None = None,
    max_events: int | None = None,
    max_moves: int | None = None,
    all_activations: bool = False,
    fast_forward: bool = True,
    force: bool = False,
    schedule: str | os.PathLike[str] | Schedule | None = None,
    then: str | None = None,
    flips: Literal["schedule", "file"] | None = None,
    progress: bool = True,
) -> Run:
    """Run an algorithm from a start to its outcome, as ``apf-viz run`` does with the same options (the
    same numbers: tests/test_api.py compares them).

    ``robots`` and ``pattern``: a shipped name, a JSON file, or the points. ``seed`` seeds the scheduler
    and, when the robots give no ``y_up``, the adversary's flips. ``algorithm``: a built-in name
    (``apf-viz run --help`` lists them) or ``module:Class`` of your own. The caps default to the run's
    budget. An unsolvable start (Theorem 1) raises :class:`~apf_viz.core.formats.InputError` unless
    ``force``.

    ``schedule`` (a schedule file, or a :class:`~apf_viz.core.schedule.Schedule`) is the adversary
    instead of ``scheduler``, as ``run --schedule``: its flips and light semantics are the run's, the run
    stops where it ends (outcome ``schedule-end``) unless ``then`` names a scheduler to go on with;
    ``flips`` chooses between the schedule's flips and the robots file's when they differ.
    ``progress``: a bar of the moves made, for a run longer than two seconds.

    >>> r = run("sym-call-7", "cup-7", seed=3)
    >>> r.outcome, r.k
    ('formed', 7)
    """
    start = start_of(robots, pattern)
    seed = _seed(seed)
    _refuse_options(max_events, max_moves, scheduler, then, light_semantics)
    chosen, plugins = chosen_algorithm(algorithm)
    if not force:
        refuse_unsolvable(start)
    followed = None
    y_up, semantics = start.flips(seed), light_semantics or "compute"
    if schedule is not None:
        followed, where = _schedule_of(schedule)
        y_up, semantics = _schedule_adversary(start, followed, where, scheduler, flips, light_semantics, seed)
    elif then is not None or flips is not None:
        raise InputError("then and flips belong to a run that follows a schedule: give schedule=")
    skip = not all_activations
    budget = run_budget(start.robots, start.pattern, skip)
    engine = Engine(
        start.robots,
        start.pattern,
        chosen,
        y_up=y_up,
        light_semantics=semantics,
        max_events=max_events or budget.max_events,
        max_moves=max_moves or budget.max_moves,
        skip_noops=skip,
        fast_forward=fast_forward,
    )
    with ProgressBar("apf-viz run", None, "moves", progress) as bar:
        if followed is None:
            _advance(engine, scheduler or DEFAULT_SCHEDULER, seed, bar)
            return Run(engine, scheduler or DEFAULT_SCHEDULER, seed, start, plugins)
        for _ in follow(engine, followed, where):
            pass
        if then is not None:
            _advance(engine, then, seed, bar)
    outcome = "schedule-end" if then is None and not engine.finished else None
    return Run(engine, "schedule", seed, start, plugins, outcome)


def _refuse_options(
    max_events: int | None,
    max_moves: int | None,
    scheduler: str | None,
    then: str | None,
    semantics: str | None,
) -> None:
    """Every bad option of :func:`run` in one line, before the run."""
    for name, cap in (("max_events", max_events), ("max_moves", max_moves)):
        if cap is not None:
            whole_number(name, cap)
    for name, given in (("scheduler", scheduler), ("then", then)):
        if given is not None and given not in AUTOMATIC:
            raise InputError(f"{name} {given!r}: choose from {', '.join(AUTOMATIC)}")
    if semantics not in (None, "compute", "lc-atomic"):
        raise InputError(f"light_semantics {semantics!r}: choose compute or lc-atomic")


STEPS_BETWEEN_REPORTS = 5_000
"""A long run says how far it is this often (the steps are the scheduler's, the same run either way)."""


def _advance(engine: Engine, scheduler: str, seed: int, bar: ProgressBar) -> None:
    """The scheduler drives the run to its end, saying its moves as it goes (a run of k = 300 takes
    seconds)."""
    chosen = make_scheduler(scheduler)
    while not engine.finished:
        advance(engine, chosen, seed, STEPS_BETWEEN_REPORTS)
        bar.to(engine.state.moves, f"{engine.state.events:,} events")


def chosen_algorithm(algorithm: str | None) -> tuple[Algorithm, dict[str, Factory]]:
    """The algorithm a call names (None: the default), a typo refused as the documented InputError."""
    if algorithm is not None and not isinstance(algorithm, str):
        raise InputError(f"algorithm {algorithm!r}: a name (apf-viz run --help lists them)")
    try:
        return algorithm_from_command_line(algorithm or DEFAULT_ALGORITHM)
    except InputError:
        raise
    except ValueError as e:
        raise InputError(str(e)) from None


def _schedule_adversary(
    start: Start,
    schedule: Schedule,
    where: str,
    scheduler: str | None,
    flips: Literal["schedule", "file"] | None,
    light_semantics: LightSemantics | None,
    seed: int,
) -> tuple[list[bool], LightSemantics]:
    """The flips and light semantics of a run that follows a schedule (``run --schedule``'s rules): the
    schedule's own; a contradiction with the robots file or ``light_semantics`` is refused."""
    if scheduler is not None:
        raise InputError(
            f"schedule is the adversary, so scheduler {scheduler!r} would be ignored; to go on under a "
            f"scheduler where the schedule ends, give then={scheduler!r}"
        )
    if flips not in (None, "schedule", "file"):
        raise InputError(f"flips {flips!r}: choose schedule or file")
    check_robots(schedule, len(start.robots), where)
    y_up, warning = adversary_flips(schedule, start.y_up, flips, where, start.robots_name)
    if warning:
        warnings.warn(warning, stacklevel=4)
    semantics: LightSemantics = schedule.light_semantics or light_semantics or "compute"
    if light_semantics and schedule.light_semantics and light_semantics != semantics:
        raise InputError(
            f"light_semantics {light_semantics!r} contradicts {where}, recorded under "
            f"{schedule.light_semantics} (leave it out to follow the schedule)"
        )
    return (list(y_up) if y_up is not None else start.flips(seed)), semantics


def follow_schedule(start: Start, algorithm: Algorithm, schedule: Schedule) -> Run:
    """A schedule a search found (a worst, a failure), played from its start with its own flips and light
    semantics: the run it was found as."""
    y_up, _ = adversary_flips(schedule, start.y_up, "schedule", "the schedule", start.robots_name)
    budget = run_budget(start.robots, start.pattern, True)
    engine = Engine(
        start.robots,
        start.pattern,
        algorithm,
        y_up=list(y_up) if y_up is not None else start.flips(1),
        light_semantics=schedule.light_semantics or "compute",
        max_events=budget.max_events,
        max_moves=budget.max_moves,
    )
    for _ in follow(engine, schedule):
        pass
    return Run(engine, "schedule", 0, start, {}, None if engine.finished else "schedule-end")


def _schedule_of(given: str | os.PathLike[str] | Schedule) -> tuple[Schedule, str]:
    if isinstance(given, Schedule):
        return given, "the schedule given"
    if isinstance(given, str | os.PathLike):
        path = Path(given)
        check_readable(path)
        return load_schedule(path), str(given)
    raise InputError(f"schedule {given!r}: a schedule file's path, or a Schedule")


def _seed(seed: int) -> int:
    """Seeds are 0 or more, everywhere (the command line's ``--seed`` and ``--seeds`` too)."""
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise InputError(f"seed {seed!r}: seeds are integers, 0 or more")
    return seed


def refuse_unsolvable(start: Start) -> None:
    """Theorem 1: a start mirror-symmetric about a robot-free horizontal line forms no pattern (unless
    it is the pattern already)."""
    refused = unsolvable_start(start.robots, start.pattern)
    if refused is not None:
        raise InputError(f"{start.robots_name}: {refused[1]}; force=True runs it anyway")


class Run:
    """A finished (or capped) run: its numbers, its events, and ways to look at it.

    The numbers are ``apf-viz run --json``'s: :attr:`outcome` (``formed``, ``collision``, ``stuck``,
    ``limit``), :attr:`moves`, :attr:`events`, :attr:`cycles`, :attr:`k`, :attr:`D` (the paper's
    max(m, n, M, N, k)) and :attr:`moves_per_kD`.
    """

    def __init__(
        self,
        engine: Engine,
        scheduler: str,
        seed: int,
        start: Start,
        plugins: Mapping[str, Factory],
        outcome: str | None = None,
    ) -> None:
        self.engine = engine
        self.scheduler = scheduler
        self.seed = seed
        self.start = start
        self._plugins = dict(plugins)
        self.summary = RunSummary.of(engine, outcome)

    def __repr__(self) -> str:
        s = self.summary
        return (
            f"<Run {s.outcome}: k={s.k}, D={s.D}, {_count(s.moves, 'move')}, {_count(s.events, 'event')}, "
            f"{s.moves_per_kD:.3f} moves/(k·D); {self.algorithm}, {self.scheduler}, "
            f"seed {self.seed}>"
        )

    @property
    def algorithm(self) -> str:
        """The algorithm's name, as ``run(algorithm=…)`` takes it."""
        return self.engine.algorithm.name

    # ------------------------------------------------------------------ the numbers
    @property
    def outcome(self) -> str:
        """How the run ended: ``formed``, ``collision``, ``stuck``, ``limit`` (or ``schedule-end``)."""
        return self.summary.outcome

    @property
    def moves(self) -> int:
        """The robots' moves, in all."""
        return self.summary.moves

    @property
    def events(self) -> int:
        """The Look, Compute and Move events the run took."""
        return self.summary.events

    @property
    def cycles(self) -> int:
        """The Look-Compute-Move cycles the robots completed."""
        return self.summary.cycles

    @property
    def k(self) -> int:
        """The number of robots."""
        return self.summary.k

    @property
    def D(self) -> int:
        """The paper's D: max(m, n, M, N, k) of the start and the pattern."""
        return self.summary.D

    @property
    def moves_per_kD(self) -> float:
        """The moves per k·D, the paper's measure of cost (rounded to 6 places)."""
        return self.summary.moves_per_kD

    @property
    def final(self) -> list[Point]:
        """Where the robots are at the end, in the order of the start."""
        return list(self.summary.final)

    def as_dict(self) -> dict[str, Any]:
        """The run's numbers as ``apf-viz run --json`` prints them."""
        data = asdict(self.summary)
        data["final"] = [list(p) for p in self.summary.final]
        return data

    # ------------------------------------------------------------------ its events
    def event_rows(self) -> list[dict[str, Any]]:
        """One row per event, in order: ``event`` (1, 2, …), ``robot``, ``phase`` (look, compute, move),
        ``rule`` (the rule a Compute fired), ``light`` (the robot's light after the event), ``x``, ``y``
        (where the robot is after it) and ``collision``."""
        positions = [list(p) for p in self.engine.start]
        lights = [self.engine.algorithm.lights[0]] * self.engine.k
        rows = []
        for i, e in enumerate(self.engine.history.events(), 1):
            if e.phase == "compute" and e.light is not None:
                lights[e.robot] = e.light
            if e.phase == "move" and e.to is not None and not e.collision:
                positions[e.robot] = list(e.to)
            x, y = positions[e.robot]
            rule = (e.rule_id or e.rule) if e.phase == "compute" else None
            rows.append(
                {"event": i, "robot": e.robot, "phase": e.phase, "rule": rule, "light": lights[e.robot],
                 "x": x, "y": y, "collision": e.collision}
            )  # fmt: skip
        return rows

    def events_table(self) -> pandas.DataFrame:
        """:meth:`event_rows` as a pandas DataFrame (pandas: the ``notebook`` extra)."""
        return _data_frame(self.event_rows())

    def positions_at(self, event: int) -> list[Point]:
        """Where every robot is after ``event`` events (0: the start)."""
        whole_number("event", event, 0, self.events, f"the run has events 0 to {self.events}")
        positions = list(self.engine.start)
        for e in self.engine.history.events()[:event]:
            if e.phase == "move" and e.to is not None and not e.collision:
                positions[e.robot] = e.to
        return positions

    # ------------------------------------------------------------------ files and pictures
    def trace(self) -> str:
        """The run as a trace file's text (``apf-viz replay``, ``serve --trace`` and the page read it)."""
        header = trace_header(self.engine, self.scheduler, self.seed)
        return trace_text(header, self.engine.history.events())

    def save_trace(self, path: str | os.PathLike[str]) -> None:
        """Write :meth:`trace` to ``path`` (atomically; only a regular file is replaced)."""
        write_file(path, self.trace())

    def schedule(self) -> str:
        """The run's schedule as a schedule file's text (who acted, step by step; the flips and the light
        semantics in its header): ``run(…, schedule=…)`` and ``apf-viz run --schedule`` replay it."""
        lines = schedule_of_steps(self.engine.history.steps)
        return schedule_text(self.engine.k, lines, self.engine.y_up, self.engine.light_semantics)

    def save_schedule(self, path: str | os.PathLike[str]) -> None:
        """Write :meth:`schedule` to ``path`` (atomically; only a regular file is replaced)."""
        write_file(path, self.schedule())

    def session(self) -> Session:
        """A visualiser session following this run's trace, at its start (what a page would show)."""
        from apf_viz.core.formats import MAX_TRACE_BYTES
        from apf_viz.workbench.session.demo import demo_session

        session = demo_session(plugins=self._plugins)
        session.load_trace("run.jsonl", self.trace().encode(), MAX_TRACE_BYTES)
        return session

    def figure(
        self, event: int | None = None, fmt: str = "svg", select: int | None = None, caption: bool = False
    ) -> str | bytes:
        """The run after ``event`` events (None: its end) as a figure, as ``apf-viz figure`` draws it:
        ``svg`` or ``tikz`` text, or ``png`` bytes (matplotlib: the ``sweep`` extra). ``select``: the robot
        whose rays are drawn; ``caption``: the caption written into the figure (``--caption``; without it,
        a bare picture for a paper's own caption)."""
        from apf_viz.figure import FORMATS
        from apf_viz.figure.export import figure_png, figure_text, run_to_event

        if fmt not in FORMATS:
            raise InputError(f"fmt {fmt!r}: choose {', '.join(FORMATS)}")
        if event is not None:
            self.positions_at(event)  # refuses an event the run has not
        if select is not None:
            whole_number("select", select, 0, self.k - 1, f"the run has robots 0 to {self.k - 1}")
        session = self.session()
        run_to_event(session, event)
        said = ""
        if caption:
            events = session.engine.state.events
            said = f"{self.start.robots_name}, {self.scheduler}, seed {self.seed}, after {events} events"
        if fmt == "png":
            return figure_png(session, select, said)
        return figure_text(session, fmt, select, said)

    def show(self, height: int = 520) -> Shown:
        """The run, played in a notebook cell: the page ``apf-viz export`` writes (viser's own recording
        and player, no server), embedded."""
        from apf_viz.ui.page_export import export_run

        whole_number("height", height, 100, 4000)
        title = f"{self.start.robots_name} → {self.start.pattern_name}, {self.scheduler}, seed {self.seed}"
        return Shown(export_run(self.session(), title).html, height)


class Shown:
    """A page a notebook shows in an output cell (its ``_repr_html_``); :attr:`html` is the page."""

    def __init__(self, page: str, height: int) -> None:
        self.html = page
        self.height = height

    def _repr_html_(self) -> str:
        return (
            f'<iframe srcdoc="{html.escape(self.html, quote=True)}" style="width: 100%; '
            f'height: {self.height}px; border: 0"></iframe>'
        )


def write_file(path: str | os.PathLike[str], text: str) -> None:
    """A file of the run's, refused in one line where it cannot be written (a folder, a missing one)."""
    if not isinstance(path, str | os.PathLike):
        raise InputError(f"{path!r}: a path to write to")
    check_writable(os.fspath(path))
    write_atomic(os.fspath(path), text)


def _data_frame(rows: list[dict[str, Any]]) -> pandas.DataFrame:
    return pandas_for("a table").DataFrame(rows)


def _count(n: int, word: str) -> str:
    """ "1 move", "2 moves"."""
    return f"{n:,} {word}" + ("" if n == 1 else "s")
