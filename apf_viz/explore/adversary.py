"""The searched adversary (``apf-viz adversary``): a costly schedule for a start of any size, where the
exact worst (explore/worst.py) is out of reach.

The search is a hill-climb over schedules. It starts from the best the built-in schedulers do (every
automatic scheduler, seeds 0–19: the bar it must beat), and tries, batch after batch, a variant of the
best schedule so far: the same first *p* steps, then (sometimes) one robot the adversary wakes out of
turn, then a built-in scheduler with a fresh seed to the end. A variant that costs more (moves or
events, to FORMED) becomes the best. The cut *p* is drawn towards the start (``p = L·u²``): what an
adversary gains, it gains by steering the leader election early (docs/ADVERSARY.md).

Every candidate is a run of the real engine, so no result exceeds what an adversary can force: where
``check --worst`` answers, the search never reports more (tests/test_adversary.py). The best is
written as a plain schedule file only after it is replayed from that file to the same count.

A batch's candidates are drawn from the search's seed and the best so far alone, and the best of a
batch is taken by its cost, ties to the first: the result is the same whether a batch runs here, one
after the other, or on a Dask cluster (``--cluster``)."""

from __future__ import annotations

import random
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Literal

from apf_viz.algorithms import get_algorithm
from apf_viz.core.budget import run_budget
from apf_viz.core.engine import Engine
from apf_viz.core.engine_core import LightSemantics
from apf_viz.core.grid import Point
from apf_viz.core.history import StepRecord
from apf_viz.core.schedule import follow, parse_schedule, schedule_of_steps, schedule_text
from apf_viz.core.schedulers import AUTOMATIC, make_scheduler, step_rng

Measure = Literal["moves", "events"]
BUILT_IN_SEEDS = range(20)
BATCH = 8  # candidates drawn and tried together (a cluster's workers take them at once)
KICK_SHARE = 0.5  # of the candidates wake one robot out of turn at the cut


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


@dataclass(frozen=True)
class Candidate:
    """A variant of the best schedule: its first ``cut`` steps, ``kick`` woken out of turn (None: no
    one), then ``scheduler`` with ``seed`` to the end."""

    cut: int
    kick: int | None
    scheduler: str
    seed: int

    def describe(self) -> str:
        kick = f", robot {self.kick} woken out of turn" if self.kick is not None else ""
        return f"the best's first {self.cut} steps{kick}, then {self.scheduler} seed {self.seed}"


@dataclass(frozen=True)
class Tried:
    """A schedule tried: its cost (None: it did not form), its steps, and how it was made."""

    value: int | None
    records: tuple[StepRecord, ...]
    source: str


def measure(engine: Engine, what: Measure) -> int | None:
    if engine.outcome != "formed":
        return None
    return engine.state.moves if what == "moves" else engine.state.events


def run_to_end(problem: Problem, prefix: Sequence[StepRecord], candidate: Candidate) -> Tried:
    """The schedule ``candidate`` makes of ``prefix`` (the best's steps), run in a fresh engine."""
    e = problem.engine()
    for record in prefix[: candidate.cut]:
        if e.finished:
            break
        e.apply(record)
    if candidate.kick is not None and not e.finished and e.eligible()[candidate.kick]:
        e.apply(StepRecord((candidate.kick,)))
    scheduler = make_scheduler(candidate.scheduler)
    while not e.finished:
        e.apply(scheduler.choose(e, step_rng(candidate.seed, e.step_index)))
    records = tuple(step.record for step in e.history.steps)
    return Tried(measure(e, problem.maximize), records, candidate.describe())


def built_in(problem: Problem, scheduler: str, seed: int) -> Tried:
    """One built-in scheduler's run, from the start."""
    return run_to_end(problem, (), Candidate(0, None, scheduler, seed))


def evaluate(problem: Problem, prefix: Sequence[StepRecord], batch: Sequence[Candidate]) -> list[Tried]:
    return [run_to_end(problem, prefix, c) for c in batch]


def draw(rng: random.Random, best: Sequence[StepRecord], k: int) -> list[Candidate]:
    """A batch of variants of ``best``, from ``rng`` alone. A cut falls where a line of the schedule
    begins (never inside a synchronous round), drawn towards the start."""
    starts = [i for i, r in enumerate(best) if r.round is None or i == 0 or best[i - 1].round != r.round]
    out = []
    for _ in range(BATCH):
        cut = starts[min(len(starts) - 1, int(len(starts) * rng.random() ** 2))] if starts else 0
        kick = rng.randrange(k) if rng.random() < KICK_SHARE else None
        out.append(Candidate(cut, kick, rng.choice(AUTOMATIC), rng.randrange(2**31)))
    return out


@dataclass
class Search:
    """The search's state: the bar (the built-ins' best), the best found, and its effort."""

    problem: Problem
    bar: Tried
    best: Tried
    evaluations: int = 0
    improvements: list[tuple[int, int]] = field(default_factory=list)  # (evaluation, value)
    seconds: float = 0.0

    @property
    def beats(self) -> bool:
        return (self.best.value or 0) > (self.bar.value or 0)


Evaluator = Callable[[Problem, Sequence[StepRecord], Sequence[Candidate]], list[Tried]]


def search(
    problem: Problem,
    budget: int,
    seed: int = 0,
    evaluator: Evaluator = evaluate,
    progress: Callable[[Search], None] = lambda s: None,
    seeds: Sequence[int] = BUILT_IN_SEEDS,
) -> Search:
    """Up to ``budget`` schedules tried (the built-ins' runs first), the best kept. KeyboardInterrupt
    ends it early: the search so far is returned (the caller writes the best found)."""
    t0 = time.perf_counter()
    firsts = [Candidate(0, None, name, s) for name in AUTOMATIC for s in seeds]
    tried = evaluator(problem, (), firsts)
    formed = [t for t in tried if t.value is not None]
    if not formed:
        raise ValueError("no built-in scheduler forms the pattern from this start: nothing to beat")
    bar = max(formed, key=lambda t: t.value or 0)
    state = Search(problem, bar, bar, len(tried))
    rng = random.Random(seed)
    k = len(problem.robots)
    try:
        while state.evaluations < budget:
            batch = draw(rng, state.best.records, k)[: budget - state.evaluations]
            results = evaluator(problem, state.best.records, batch)
            state.evaluations += len(batch)
            top = max(range(len(results)), key=lambda i: (results[i].value or -1, -i))
            if (results[top].value or -1) > (state.best.value or -1):
                state.best = results[top]
                state.improvements.append((state.evaluations, results[top].value or 0))
            state.seconds = time.perf_counter() - t0
            progress(state)
    except KeyboardInterrupt:
        pass
    state.seconds = time.perf_counter() - t0
    return state


def best_schedule_text(state: Search) -> str:
    """The best found as a schedule file (its flips and light semantics in the header), replayed from
    that text to the same cost first: a schedule that does not replay to its count is refused."""
    p = state.problem
    e = p.engine()
    for record in state.best.records:
        e.apply(record)
    text = schedule_text(len(p.robots), schedule_of_steps(e.history.steps), p.y_up, p.light_semantics)
    replayed = p.engine()
    for _ in follow(replayed, parse_schedule(text)):
        pass
    if measure(replayed, p.maximize) != state.best.value:
        raise RuntimeError(
            f"the schedule found replays to {measure(replayed, p.maximize)} {p.maximize}, "
            f"not {state.best.value}: not written"
        )
    return text
