"""One run from Python: :func:`run` drives the same engine, budget and scheduler as ``apf-viz run``, and
returns a :class:`Run` to read, tabulate, draw, show in a notebook and save."""

from __future__ import annotations

import html
import os
from collections.abc import Mapping
from dataclasses import asdict
from typing import TYPE_CHECKING, Any

from apf_viz.algorithms import DEFAULT_ALGORITHM, Factory, algorithm_from_command_line
from apf_viz.api.inputs import Points, Start, start_of
from apf_viz.api.tables import pandas_for
from apf_viz.core.budget import run_budget
from apf_viz.core.engine import Engine, LightSemantics
from apf_viz.core.files import write_atomic
from apf_viz.core.formats import InputError, trace_text
from apf_viz.core.grid import Point
from apf_viz.core.run import RunSummary, advance, trace_header
from apf_viz.core.schedulers import AUTOMATIC, DEFAULT_SCHEDULER, make_scheduler
from apf_viz.core.symmetry import unsolvable_start

if TYPE_CHECKING:
    import pandas

    from apf_viz.workbench.session import Session


def run(
    robots: Points,
    pattern: Points,
    *,
    scheduler: str = DEFAULT_SCHEDULER,
    seed: int = 1,
    algorithm: str | None = None,
    light_semantics: LightSemantics = "compute",
    max_events: int | None = None,
    max_moves: int | None = None,
    all_activations: bool = False,
    fast_forward: bool = True,
    force: bool = False,
) -> Run:
    """Run an algorithm from a start to its outcome, as ``apf-viz run`` does with the same options (the
    same numbers: tests/test_api.py compares them).

    ``robots`` and ``pattern``: a shipped name, a JSON file, or the points. ``seed`` seeds the scheduler
    and, when the robots give no ``y_up``, the adversary's flips. ``algorithm``: a built-in name
    (``apf-viz run --help`` lists them) or ``module:Class`` of your own. The caps default to the run's
    budget. An unsolvable start (Theorem 1) raises :class:`~apf_viz.core.formats.InputError` unless
    ``force``.

    >>> r = run("sym-call-7", "cup-7", seed=3)
    >>> r.outcome, r.k
    ('formed', 7)
    """
    start = start_of(robots, pattern)
    seed = _seed(seed)
    if scheduler not in AUTOMATIC:
        raise InputError(f"scheduler {scheduler!r}: choose from {', '.join(AUTOMATIC)}")
    if light_semantics not in ("compute", "lc-atomic"):
        raise InputError(f"light_semantics {light_semantics!r}: choose compute or lc-atomic")
    chosen, plugins = algorithm_from_command_line(algorithm or DEFAULT_ALGORITHM)
    if not force:
        refuse_unsolvable(start)
    skip = not all_activations
    budget = run_budget(start.robots, start.pattern, skip)
    engine = Engine(
        start.robots,
        start.pattern,
        chosen,
        y_up=start.flips(seed),
        light_semantics=light_semantics,
        max_events=max_events or budget.max_events,
        max_moves=max_moves or budget.max_moves,
        skip_noops=skip,
        fast_forward=fast_forward,
    )
    advance(engine, make_scheduler(scheduler), seed)
    return Run(engine, scheduler, seed, start, plugins)


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
        self, engine: Engine, scheduler: str, seed: int, start: Start, plugins: Mapping[str, Factory]
    ) -> None:
        self.engine = engine
        self.scheduler = scheduler
        self.seed = seed
        self.start = start
        self._plugins = dict(plugins)
        self.summary = RunSummary.of(engine)

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
        return self.summary.outcome

    @property
    def moves(self) -> int:
        return self.summary.moves

    @property
    def events(self) -> int:
        return self.summary.events

    @property
    def cycles(self) -> int:
        return self.summary.cycles

    @property
    def k(self) -> int:
        return self.summary.k

    @property
    def D(self) -> int:
        return self.summary.D

    @property
    def moves_per_kD(self) -> float:
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
        if not 0 <= event <= self.events:
            raise InputError(f"event {event}: the run has events 0 to {self.events}")
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
        write_atomic(os.fspath(path), self.trace())

    def session(self) -> Session:
        """A visualiser session following this run's trace, at its start (what a page would show)."""
        from apf_viz.core.formats import MAX_TRACE_BYTES
        from apf_viz.workbench.session.demo import demo_session

        session = demo_session(plugins=self._plugins)
        session.load_trace("run.jsonl", self.trace().encode(), MAX_TRACE_BYTES)
        return session

    def figure(self, event: int | None = None, fmt: str = "svg", select: int | None = None) -> str | bytes:
        """The run after ``event`` events (None: its end) as a figure: ``svg`` or ``tikz`` text, or
        ``png`` bytes (matplotlib: the ``sweep`` extra). ``select``: the robot whose rays are drawn."""
        from apf_viz.figure.export import figure_png, figure_text, run_to_event

        session = self.session()
        run_to_event(session, event)
        if fmt == "png":
            return figure_png(session, select)
        return figure_text(session, fmt, select)

    def show(self, height: int = 520) -> Shown:
        """The run, played in a notebook cell: the page ``apf-viz export`` writes (viser's own recording
        and player, no server), embedded."""
        from apf_viz.ui.page_export import export_run

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


def _data_frame(rows: list[dict[str, Any]]) -> pandas.DataFrame:
    return pandas_for("a table").DataFrame(rows)


def _count(n: int, word: str) -> str:
    """ "1 move", "2 moves"."""
    return f"{n:,} {word}" + ("" if n == 1 else "s")
