"""The searched adversary (``apf-viz adversary``): a costly schedule for a start of any size, where the
exact worst (explore/worst.py) may be out of reach.

It starts from every automatic built-in scheduler over seeds 0–19 (their best is the bar it must beat).
Then beams of width 64, 128, … (:func:`_beams`, explore/beam.py) search the exact worst's own state
graph a layer of events at a time, until one is never cut: that one is the exact worst. The rest of the
budget varies the :data:`KEPT` costliest schedules seen, best-first: each choice they made tried
differently — the same first steps, another robot woken there (or, at a synchronous round, the round
without one of its robots), then the same scheduler and seed to the end — the costliest schedule's
choices first, its earliest first. Most steps of this algorithm leave one robot anything to do, so the
choices are few; a run notes where it had them (:func:`run_to_end`). A share of the tries are fresh
starts (a built-in scheduler with a new seed).

Every candidate is a run of the real engine, so no result exceeds what an adversary can force: where
``check --worst`` answers, the search never reports more (tests/test_adversary.py). The best is
written as a plain schedule file only after it is replayed from that file to the same count.

What is tried next depends on the search's seed and the results so far alone, never on which
worker finished first: the result is the same whether a batch runs here, one schedule after the other,
or on a Dask cluster (``--cluster``; the beams run here)."""

from __future__ import annotations

import heapq
import random
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from apf_viz.algorithms import get_algorithm
from apf_viz.core.budget import run_budget
from apf_viz.core.engine import Engine
from apf_viz.core.engine_core import LightSemantics
from apf_viz.core.grid import Point
from apf_viz.core.history import StepRecord
from apf_viz.core.schedule import Found, follow, parse_schedule, schedule_of_steps, schedule_text
from apf_viz.core.schedulers import AUTOMATIC, make_scheduler, step_rng
from apf_viz.explore.beam import Beamed, beam

Measure = Literal["moves", "events"]
BUILT_IN_SEEDS = range(20)
FAILURES = frozenset({"collision", "stuck"})  # engine outcomes that are the algorithm's failures
BATCH = 8  # candidates drawn and tried together (a cluster's workers take them at once)
KEPT = 16  # schedules the search varies: the costliest seen
FRESH_SHARE = 0.2  # of the candidates, those that start afresh (a built-in scheduler, a new seed)
FIRST_WIDTH = 64  # the first beam's (explore/beam.py); each next one is twice as wide
WIDTH = 512  # the widest beam, by default: 64, 128, 256, 512 (on a k = 5 start 256 was never cut)


@dataclass(frozen=True)
class Problem:
    """What the adversary plays against: the algorithm (by name, so that a worker builds its own), the
    start, the pattern, the flips (the start's: the same as the built-ins are measured with) and what
    it maximises."""

    algorithm: str
    robots: tuple[Point, ...]
    pattern: tuple[Point, ...]
    y_up: tuple[bool, ...]
    maximize: Measure = "moves"
    light_semantics: LightSemantics = "compute"

    def engine(self) -> Engine:
        budget = run_budget(list(self.robots), list(self.pattern), True)
        return Engine(
            list(self.robots), list(self.pattern), get_algorithm(self.algorithm), y_up=list(self.y_up),
            max_events=budget.max_events, light_semantics=self.light_semantics,
        )  # fmt: skip

    def replayed(self, records: Sequence[StepRecord]) -> Engine:
        """A fresh engine that has taken ``records`` (a schedule found): its history and counts."""
        e = self.engine()
        for record in records:
            e.apply(record)
        return e


@dataclass(frozen=True)
class Candidate:
    """A variant of the best schedule: its first ``cut`` steps, then another choice there — robot
    ``kick`` woken instead (ASYNC), or, where the best began a synchronous round, that round without
    robot ``kick`` (``drop``) — then ``scheduler`` with ``seed`` to the end."""

    cut: int
    kick: int | None
    scheduler: str
    seed: int
    drop: tuple[int, ...] = ()  # the round the best began at the cut (with ``kick`` left out of it)

    def first(self, round_now: int) -> StepRecord | None:
        """The step taken at the cut instead of the best's."""
        if self.kick is None:
            return None
        if self.drop:
            return StepRecord(tuple(r for r in self.drop if r != self.kick), round=round_now + 1)
        return StepRecord((self.kick,))

    def describe(self) -> str:
        kick = ""
        if self.kick is not None:
            kick = (
                f", robot {self.kick} left out of that round"
                if self.drop
                else f", robot {self.kick} woken instead"
            )
        return f"the best's first {self.cut} steps{kick}, then {self.scheduler} seed {self.seed}"


@dataclass(frozen=True)
class Tried:
    """A schedule tried: its cost (None: it did not form), its steps, how it was made, and the scheduler
    and seed that ran its end (a variant of it goes on the same way, unless it draws another)."""

    value: int | None
    records: tuple[StepRecord, ...]
    source: str
    policy: tuple[str, int] = ("async", 0)
    choices: tuple[tuple[int, tuple[int, ...]], ...] = ()  # (step, the robots that could act there)
    outcome: str | None = None  # how its run ended (the engine's outcome)

    @property
    def failed(self) -> bool:
        """It ended in a collision or stuck short of the pattern: a failure of the algorithm, no cost."""
        return self.outcome in FAILURES


def measure(engine: Engine, what: Measure) -> int | None:
    if engine.outcome != "formed":
        return None
    return engine.state.moves if what == "moves" else engine.state.events


def run_to_end(problem: Problem, prefix: Sequence[StepRecord], candidate: Candidate) -> Tried:
    """The schedule ``candidate`` makes of ``prefix`` (the best's steps), run in a fresh engine; where
    it had a choice is noted on the way (:func:`decisions` reads it, on the machine that searches)."""
    e = problem.engine()
    choices: list[tuple[int, tuple[int, ...]]] = []
    for record in prefix[: candidate.cut]:
        if e.finished:
            break
        _apply(e, record, choices)
    first = candidate.first(e.state.round)
    if first is not None and not e.finished and e.eligible()[list(first.robots)].all():
        _apply(e, first, choices)
    scheduler = make_scheduler(candidate.scheduler)
    while not e.finished:
        _apply(e, scheduler.choose(e, step_rng(candidate.seed, e.step_index)), choices)
    records = tuple(step.record for step in e.history.steps)
    policy = (candidate.scheduler, candidate.seed)
    return Tried(
        measure(e, problem.maximize), records, candidate.describe(), policy, tuple(choices), e.outcome
    )


def _apply(e: Engine, record: StepRecord, choices: list[tuple[int, tuple[int, ...]]]) -> None:
    """``record`` applied, and the robots that could have acted instead noted, where there were others."""
    could = tuple(np.flatnonzero(e.eligible()).tolist())
    if len(could) > 1 or could != tuple(record.robots):
        choices.append((len(e.history.steps), could))
    e.apply(record)


def built_in(problem: Problem, scheduler: str, seed: int) -> Tried:
    """One built-in scheduler's run, from the start."""
    return run_to_end(problem, (), Candidate(0, None, scheduler, seed))


def line_starts(records: Sequence[StepRecord]) -> list[int]:
    """The steps where a line of the schedule begins: every ASYNC step, a synchronous round's first."""
    return [i for i, r in enumerate(records) if r.round is None or i == 0 or records[i - 1].round != r.round]


def decisions(problem: Problem, best: Tried) -> list[Candidate]:
    """Every choice the best schedule made where it had another: at each line's start, each other robot
    that could act there (most steps of this algorithm leave one robot anything to do), woken instead
    and the best's scheduler and seed to the end; at a synchronous round's start, the round without one
    of its robots. The robots that could act are those its run noted (:func:`run_to_end`): no replay."""
    could = dict(best.choices)
    out = []
    for i in line_starts(best.records):
        record = best.records[i]
        if record.round is not None and len(record.robots) > 1:  # the round, one robot fewer
            out += [Candidate(i, r, *best.policy, drop=tuple(record.robots)) for r in record.robots]
        out += [Candidate(i, r, *best.policy) for r in could.get(i, ()) if (r,) != tuple(record.robots)]
    return out


def beamed(
    problem: Problem, width: int, seed: int, progress: Callable[[int, int], None] = lambda d, n: None
) -> tuple[Tried, Beamed]:
    """The beam's costliest path (explore/beam.py) as a run of the real engine; a path that does not
    end formed there (none has, so far) is no schedule: its cost is None."""
    e = problem.engine()
    found = beam(
        problem.algorithm, problem.robots, problem.pattern, problem.y_up, problem.maximize, width, seed,
        problem.light_semantics, progress, max_layers=e.max_events or 10_000_000,
    )  # fmt: skip
    choices: list[tuple[int, tuple[int, ...]]] = []
    for group in found.schedule:
        if e.finished:
            break
        _apply(e, StepRecord(group), choices)
    source = (
        f"a beam of width {width} over the adversary's choices ({found.states:,} states, "
        f"{found.layers:,} events deep{', cut' if found.cut else ', never cut: every path'})"
    )
    records = tuple(step.record for step in e.history.steps)
    value = measure(e, problem.maximize) if e.finished else None
    return Tried(value, records, source, choices=tuple(choices), outcome=e.outcome), found


def beamed_failure(problem: Problem, found: Beamed) -> Tried | None:
    """The failure the beam met (a collision, or a quiet state short of the pattern) as a run of the real
    engine, if it replays to one there."""
    if found.failure is None:
        return None
    kind, schedule = found.failure
    e = problem.engine()
    for group in schedule:
        if e.finished:
            break
        e.apply(StepRecord(group))
    if not e.finished:
        e.settle_outcome()  # a path that ends where nobody can act: stuck (the engine decides it so)
    records = tuple(step.record for step in e.history.steps)
    return Tried(None, records, f"a beam's path to a {kind}", outcome=e.outcome)


def draw(rng: random.Random) -> Candidate:
    """A fresh start: a built-in scheduler and a seed drawn afresh, from the start."""
    return Candidate(0, None, rng.choice(AUTOMATIC), rng.randrange(2**31))


@dataclass
class Search:
    """The search's state: the bar (the built-ins' best), the best found, and its effort."""

    problem: Problem
    bar: Tried
    best: Tried
    evaluations: int = 0  # schedules searched (the budget), beside the built-ins' runs
    beam: Beamed | None = None  # the last beam's effort, when one ran
    doing: str = ""  # what the search is doing, while it is not trying schedules (for its progress)
    improvements: list[tuple[int, int]] = field(default_factory=list)  # (evaluation, value)
    seconds: float = 0.0
    failure: Tried | None = None  # the first schedule met on which the algorithm fails: no maximum then
    bar_runs: int = 0  # the built-in schedulers' runs that set the bar (not counted in the budget)

    @property
    def exact(self) -> bool:
        """A beam never cut followed every path: its answer is the exact worst, no variant can beat it."""
        beam = self.beam
        return beam is not None and not beam.cut and beam.value is not None and self.best.value == beam.value

    @property
    def beats(self) -> bool:
        return (self.best.value or 0) > (self.bar.value or 0)


Job = tuple[Sequence[StepRecord], Candidate]  # a candidate and the schedule it varies
Evaluator = Callable[[Problem, Sequence[Job]], list[Tried]]


def evaluate(problem: Problem, jobs: Sequence[Job]) -> list[Tried]:
    return [run_to_end(problem, prefix, candidate) for prefix, candidate in jobs]


class Frontier:
    """The schedules worth varying: the :data:`KEPT` costliest seen (each once), and the choices of
    each not yet tried, the costliest schedule's first, its earliest choices first."""

    def __init__(self, problem: Problem) -> None:
        self.problem = problem
        self.kept: list[Tried] = []
        self._seen: set[int] = set()
        # A heap: the costliest schedule's choices first, of equal costs the newest schedule's, its
        # choices in order (the earliest first).
        self._todo: list[tuple[int, int, int, Tried, Candidate]] = []
        self._order = 0

    def offer(self, tried: Tried) -> None:
        """A schedule tried: kept, and its choices queued, if it is among the costliest and new."""
        key = hash(tried.records)
        if tried.value is None or key in self._seen:
            return
        if len(self.kept) >= KEPT and tried.value < (self.kept[-1].value or 0):
            return
        self._seen.add(key)
        # Stable: a new schedule goes before those of its cost, so a plateau of equal costs is walked.
        self.kept = sorted([tried, *self.kept], key=lambda t: -(t.value or 0))[:KEPT]
        self._order += 1
        for n, candidate in enumerate(decisions(self.problem, tried)):
            heapq.heappush(self._todo, (-(tried.value or 0), -self._order, n, tried, candidate))

    def take(self) -> Job | None:
        if not self._todo:
            return None
        _, _, _, tried, candidate = heapq.heappop(self._todo)
        return tried.records, candidate


def search(
    problem: Problem,
    budget: int,
    seed: int = 0,
    evaluator: Evaluator = evaluate,
    progress: Callable[[Search], None] = lambda s: None,
    seeds: Sequence[int] = BUILT_IN_SEEDS,
    width: int = WIDTH,
) -> Search:
    """The built-in schedulers' runs (the bar: one per scheduler and seed, not counted in the budget),
    then up to ``budget`` schedules searched, the costliest kept: beams, then a best-first search over
    the choices the costliest schedules made (:class:`Frontier`), with now and then a fresh start.
    KeyboardInterrupt ends it early: the search so far is returned (the caller writes its best)."""
    t0 = time.perf_counter()
    firsts: list[Job] = [((), Candidate(0, None, name, s)) for name in AUTOMATIC for s in seeds]
    tried = _built_ins(problem, firsts, evaluator, progress, t0)
    formed = [t for t in tried if t.value is not None]
    failed = next((t for t in tried if t.failed), None)
    if not formed and failed is None:
        raise ValueError("no built-in scheduler forms the pattern from this start: nothing to beat")
    bar = max(formed, key=lambda t: t.value or 0) if formed else failed
    assert bar is not None
    state = Search(problem, bar, bar, 0, failure=failed, bar_runs=len(tried))
    if failed is not None:  # a failure is the answer: there is no costliest schedule to look for
        state.seconds = time.perf_counter() - t0
        return state
    frontier = Frontier(problem)
    for t in tried:
        frontier.offer(t)
    rng = random.Random(seed)
    try:
        _beams(state, frontier, budget, width, seed, progress, t0)
        # A beam never cut followed every path: its answer is the exact worst, and no variant can beat it.
        while state.evaluations < budget and state.failure is None and not state.exact:
            jobs: list[Job] = []
            for _ in range(min(BATCH, budget - state.evaluations)):
                job = frontier.take() if rng.random() >= FRESH_SHARE else None
                jobs.append(job if job is not None else ((), draw(rng)))
            results = evaluator(problem, jobs)
            state.evaluations += len(jobs)
            for result in results:
                _better(state, result)
                frontier.offer(result)
                if result.failed and state.failure is None:
                    state.failure = result
            state.seconds = time.perf_counter() - t0
            progress(state)
    except KeyboardInterrupt:
        pass
    state.seconds = time.perf_counter() - t0
    return state


def _built_ins(
    problem: Problem,
    firsts: list[Job],
    evaluator: Evaluator,
    progress: Callable[[Search], None],
    t0: float,
) -> list[Tried]:
    """The built-in schedulers' runs, a batch at a time, saying how far they are (on a far start each
    run is long: the search must not sit silent through them)."""
    tried: list[Tried] = []
    for i in range(0, len(firsts), BATCH):
        tried.extend(evaluator(problem, firsts[i : i + BATCH]))
        so_far = max(tried, key=lambda t: t.value or -1)
        shown = Search(problem, so_far, so_far, 0, bar_runs=len(tried))
        shown.doing = f"the built-in schedulers' runs: {len(tried)} of {len(firsts)}"
        shown.seconds = time.perf_counter() - t0
        progress(shown)
    return tried


def _beams(
    state: Search,
    frontier: Frontier,
    budget: int,
    width: int,
    seed: int,
    progress: Callable[[Search], None],
    t0: float,
) -> None:
    """Beams of width 64, 128, … up to ``width`` (each one evaluation of the budget), until one is never
    cut: that one followed every path, and no wider beam can find more."""
    problem = state.problem
    w = min(FIRST_WIDTH, width)
    deep = max(1, len(state.bar.records))  # about as deep as the beam goes: the costliest run's steps
    while 0 < w <= width and state.evaluations < budget:
        began = time.perf_counter()

        def deeper(layers: int, states: int, w: int = w, began: float = began) -> None:
            rate = layers / max(time.perf_counter() - began, 1e-9)
            eta = max(deep - layers, 0) / rate
            state.doing = (
                f"a beam of width {w}: {layers:,} of about {deep:,} events deep, {states:,} states, "
                f"ETA about {eta:.0f} s"
            )
            state.seconds = time.perf_counter() - t0
            progress(state)

        found, state.beam = beamed(problem, w, seed, deeper)
        state.doing = ""
        state.evaluations += 1
        state.failure = beamed_failure(problem, state.beam)
        if state.failure is not None:
            break
        _better(state, found)
        frontier.offer(found)
        state.seconds = time.perf_counter() - t0
        progress(state)
        if not state.beam.cut:
            break
        w *= 2


def _better(state: Search, result: Tried) -> None:
    if (result.value or -1) > (state.best.value or -1):
        state.best = result
        state.improvements.append((state.evaluations, result.value or 0))


def best_schedule_text(state: Search) -> str:
    """The best found as a schedule file (its flips and light semantics in the header), replayed from
    that text to the same cost first: a schedule that does not replay to its count is refused."""
    p = state.problem
    e = p.replayed(state.best.records)
    found = Found(
        maximize=p.maximize,
        value=state.best.value or 0,
        built_ins=state.bar.value or 0,
        tried=state.bar_runs + state.evaluations,
    )
    text = schedule_text(len(p.robots), schedule_of_steps(e.history.steps), p.y_up, p.light_semantics, found)
    replayed = p.engine()
    for _ in follow(replayed, parse_schedule(text)):
        pass
    if measure(replayed, p.maximize) != state.best.value:
        raise RuntimeError(
            f"the schedule found replays to {measure(replayed, p.maximize)} {p.maximize}, "
            f"not {state.best.value}: not written"
        )
    return text


def failure_schedule_text(state: Search) -> str:
    """The failure the search met as a schedule file (flips and light semantics in its header), replayed
    from that text to the same outcome first."""
    p = state.problem
    assert state.failure is not None
    e = p.replayed(state.failure.records)
    text = schedule_text(len(p.robots), schedule_of_steps(e.history.steps), p.y_up, p.light_semantics)
    replayed = p.engine()
    for _ in follow(replayed, parse_schedule(text)):
        pass
    if not replayed.finished:
        replayed.settle_outcome()
    if replayed.outcome != state.failure.outcome:
        raise RuntimeError(f"the failing schedule replays to {replayed.outcome}, not {state.failure.outcome}")
    return text
