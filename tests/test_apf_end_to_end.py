"""End to end: the paper's algorithm (resolved) forms every demo pattern and random patterns from random
solvable starts under every scheduler, checked by the audit (independent of the engine's verdict):
formed, no collision, ≤ 8 lights, never two robots with light leader, all lights done at the end; and
on every decision, explain() on the snapshot it used gives that very decision, with a registered id."""

from __future__ import annotations

import json
import random

import pytest

from apf_viz.algorithms import get_algorithm
from apf_viz.algorithms.apf_opaque_grid.audit import audit_run, random_pattern, random_solvable_start
from apf_viz.algorithms.apf_opaque_grid.rules import RULE_IDS
from apf_viz.core.engine import Engine
from apf_viz.core.portrayal import explain
from apf_viz.demos import demo_files

SCHEDULERS = ["fsync", "ssync", "async", "stale-first", "round-robin"]
DEMOS = list(demo_files().values())  # the patterns (scenarios.json beside them is not one)


def explanation_is_the_decision(engine: Engine, robot: int) -> None:
    """explain() on the snapshot this Compute used gives the decision the engine took, and its rule id."""
    view = engine.state.decided[robot]
    explained = explain(engine.algorithm, view, engine.pattern)
    assert explained.decision == engine.state.pending[robot], (view, explained.decision)
    assert explained.decision.rule_id in RULE_IDS or "/" in explained.decision.rule_id


def check(start, pattern, scheduler, seed, light_semantics="compute"):
    rng = random.Random(seed)
    y_up = [rng.random() < 0.5 for _ in start]
    engine = Engine(
        start,
        pattern,
        get_algorithm("apf-opaque-grid"),
        y_up=y_up,
        max_events=3_000_000,
        light_semantics=light_semantics,
    )
    audit = audit_run(engine, scheduler, seed, on_compute=explanation_is_the_decision)
    assert audit.ok, (start, y_up, pattern, scheduler, seed, audit.problems)
    # One leader is elected, unless the start already is the pattern (formed at time 0, no event).
    assert audit.max_leaders == (1 if audit.events else 0) and len(audit.lights_used) <= 8


@pytest.mark.parametrize("scheduler", SCHEDULERS)
@pytest.mark.parametrize("demo", DEMOS, ids=[p.stem for p in DEMOS])
def test_every_demo_pattern_forms(demo, scheduler):
    pattern = [tuple(p) for p in json.loads(demo.read_text())["points"]]
    rng = random.Random(demo.stem)
    start = random_solvable_start(len(pattern), rng)
    check(start, pattern, scheduler, seed=rng.randrange(1000))


@pytest.mark.parametrize("scheduler", SCHEDULERS)
@pytest.mark.parametrize("k", range(1, 31))
def test_random_starts_k_1_to_30(k, scheduler):
    rng = random.Random(1000 + k)
    start = random_solvable_start(k, rng)
    pattern = random_pattern(k, rng)
    check(start, pattern, scheduler, seed=k)


@pytest.mark.parametrize("seed", range(40))
def test_small_starts_several_seeds_both_light_semantics(seed):
    rng = random.Random(seed)
    k = rng.randint(2, 8)
    start = random_solvable_start(k, rng, box=4)
    pattern = random_pattern(k, rng, box=4)
    for scheduler in ("async", "stale-first"):
        check(start, pattern, scheduler, seed)
        check(start, pattern, scheduler, seed, light_semantics="lc-atomic")
