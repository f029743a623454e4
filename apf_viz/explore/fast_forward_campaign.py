"""The fast-forward campaign: generated adversarial starts (:mod:`apf_viz.core.adversarial_starts`), each
run twice, with walks and step by step, under every scheduler, both light semantics and caps that fall
inside a walk; the two runs must be the same event for event, and no stride promise may be broken.

``scripts/fast_forward_campaign.py`` runs thousands (docs/VERIFICATION.md, "Fast-forward, generated");
``tests/test_fast_forward.py`` a few hundred.
"""

from __future__ import annotations

import random
from collections.abc import Iterator
from dataclasses import dataclass

from apf_viz.algorithms import get_algorithm
from apf_viz.core.adversarial_starts import FAMILIES, Case, generate
from apf_viz.core.budget import run_budget
from apf_viz.core.engine import Engine
from apf_viz.core.run import advance
from apf_viz.core.schedulers import kind_of, make_scheduler, ordered

# Numbered cases keep their scheduler: the order the campaign was first run in, then any added since.
SCHEDULERS = ordered(("async", "stale-first", "round-robin", "fsync", "ssync"))
WALKING = tuple(s for s in SCHEDULERS if kind_of(s).forced_when_alone)  # forced when alone: walks happen


@dataclass(frozen=True)
class Trial:
    """One comparison: a generated start, the adversary, the light semantics and the caps."""

    case: Case
    seed: int
    scheduler: str
    semantics: str
    algorithm: str
    max_moves: int | None
    max_events: int | None

    def describe(self) -> str:
        caps = f" max_moves={self.max_moves}" if self.max_moves else ""
        caps += f" max_events={self.max_events}" if self.max_events else ""
        return (
            f"{self.case.family} robots={self.case.robots} y_up={self.case.y_up} pattern={self.case.pattern} "
            f"--scheduler {self.scheduler} --seed {self.seed} --light-semantics {self.semantics} "
            f"--algorithm {self.algorithm}{caps}"
        )


@dataclass(frozen=True)
class Result:
    trial: Trial
    outcome: str
    events: int
    walks: int  # macro-steps the run with walks took
    forced: int  # runs of forced cycles it took
    mismatch: str | None


def trials(count: int, first: int = 0, far: int = 1000) -> Iterator[Trial]:
    """``count`` trials from seed ``first`` on: families in turn, every scheduler (the walking ones
    twice as often), lc-atomic one time in four, the literal paper one time in eight, a cap inside the
    run one time in four."""
    families = sorted(FAMILIES)
    for i in range(first, first + count):
        rng = random.Random(f"trial:{i}")
        case = generate(families[i % len(families)], i, far=far)
        scheduler = rng.choice(SCHEDULERS + WALKING)
        semantics = "lc-atomic" if rng.random() < 0.25 else "compute"
        algorithm = "apf-opaque-grid-literal" if rng.random() < 0.125 else "apf-opaque-grid"
        cap = int(10 * 1000 ** rng.random()) if rng.random() < 0.25 else None
        on_moves = rng.random() < 0.5
        yield Trial(
            case,
            i,
            scheduler,
            semantics,
            algorithm,
            cap if cap and on_moves else None,
            3 * cap if cap and not on_moves else None,
        )


def _engine(trial: Trial, fast: bool) -> Engine:
    case = trial.case
    budget = run_budget(case.robots, case.pattern, True)
    return Engine(
        case.robots,
        case.pattern,
        get_algorithm(trial.algorithm),
        y_up=case.y_up,
        light_semantics=trial.semantics,  # type: ignore[arg-type]
        max_moves=trial.max_moves or min(budget.max_moves, 200_000),
        max_events=trial.max_events or min(budget.max_events, 600_000),
        fast_forward=fast,
    )


def run_state(e: Engine) -> tuple:
    """Everything a run's future and its reports depend on (not the engine's caches)."""
    st = e.state
    return (
        st.outcome,
        e.current_points(),
        list(st.lights),
        st.phase.tolist(),
        (st.steps, st.events, st.moves, st.cycles, st.skipped, st.version),
        st.look_step.tolist(),
        st.last_act.tolist(),
        st.last_cycle_end.tolist(),
        st.decided,
        st.decided_seen,
        st.decided_look.tolist(),
        sorted(st.lights_used),
    )


def compare(trial: Trial) -> Result:
    """Both runs to their end; the first difference, if any, named."""
    slow, fast = _engine(trial, False), _engine(trial, True)
    scheduler = make_scheduler(trial.scheduler)
    advance(slow, scheduler, trial.seed)
    advance(fast, make_scheduler(trial.scheduler), trial.seed)
    mismatch = None
    if fast.broken_strides:
        mismatch = f"{fast.broken_strides} stride promise(s) broken at the walk's last cycle"
    a, b = slow.history.events(), fast.history.events()
    if a != b:
        at = next((i for i, (x, y) in enumerate(zip(a, b, strict=False)) if x != y), min(len(a), len(b)))
        mismatch = f"events differ from event {at} (step by step {len(a)} events, with walks {len(b)})"
    elif run_state(slow) != run_state(fast):
        mismatch = "same events, different final state"
    outcome = slow.outcome or "running"
    return Result(trial, outcome, slow.state.events, fast.walks, fast.forced_walks, mismatch)
