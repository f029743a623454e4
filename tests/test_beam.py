"""The beam over the adversary's choices (explore/beam.py): where no layer is cut it has searched every
path, and its answer is the exact worst of ``check --worst``; where it is cut it never answers more."""

from __future__ import annotations

import random

import pytest

from apf_viz.algorithms import get_algorithm
from apf_viz.algorithms.apf_opaque_grid.audit import random_pattern, random_solvable_start
from apf_viz.core.adversarial_starts import FAMILIES, generate
from apf_viz.core.engine import Engine
from apf_viz.explore.beam import beam
from apf_viz.explore.beam_campaign import against_exact
from apf_viz.explore.explorer import Explorer
from apf_viz.explore.worst import worst
from apf_viz.sweeps.cells import generated_start

ALGORITHM = "apf-opaque-grid"


def generated(n: int, seed: int):
    rng = random.Random(seed)
    for _ in range(n):
        k = rng.choice((3, 4, 5))
        start, pattern = random_solvable_start(k, rng), random_pattern(k, rng)
        yield start, pattern, tuple(rng.random() < 0.5 for _ in range(k)), rng.choice(("moves", "events"))


CASES = list(generated(24, 17)) + [(*generated_start(5, s), "moves") for s in (3, 5, 8)]


@pytest.mark.parametrize("case", CASES, ids=lambda c: f"k{len(c[0])}-{c[3]}")
def test_an_uncut_beam_is_the_exact_worst_and_a_cut_one_never_more(case):
    robots, pattern, y_up, measure = case
    exact = worst(get_algorithm(ALGORITHM), robots, pattern, [y_up], measure, max_states=300_000)
    if exact.value is None:
        pytest.skip(f"no maximum to compare with: {exact.detail}")  # a failing start: no worst exists
    whole = beam(ALGORITHM, robots, pattern, y_up, measure, width=10**6)
    narrow = beam(ALGORITHM, robots, pattern, y_up, measure, width=2, seed=3)
    assert not whole.cut and whole.value == exact.value
    assert narrow.value is not None and narrow.value <= exact.value
    for found in (whole, narrow):  # the path is a run of the real engine, formed at exactly its cost
        e = Engine(robots, pattern, get_algorithm(ALGORITHM), y_up=list(y_up))
        for group in found.schedule:
            e.step(group)
        assert e.outcome == "formed"
        assert (e.state.moves if measure == "moves" else e.state.events) == found.value


def test_an_asynchronous_search_of_thirty_robots_makes_no_rounds():
    """The 2^k groups a synchronous round may take are made only for a round: at k = 30 they were a
    billion tuples, and the exact worst of a 30-robot start ran out of memory before its first state."""
    robots, pattern, y_up = generated_start(30, 1)
    algorithm = get_algorithm(ALGORITHM)
    explorer = Explorer(algorithm, robots, pattern, y_up, scheduler="async", eligible_only=True)
    out: list = []
    explorer.eligible_edges(explorer.initial(), (0, 0), out)
    assert out and "groups" not in vars(explorer.space)


FAMILY_CASES = [
    (generate(family, seed, far=12), ("moves", "events")[seed % 2])
    for family in FAMILIES
    for seed in range(6)
]


@pytest.mark.slow
@pytest.mark.parametrize("case", FAMILY_CASES, ids=lambda c: f"{c[0].family}-k{len(c[0].robots)}-{c[1]}")
def test_on_the_adversarial_families_the_beam_agrees_with_the_exact_worst(case):
    """The campaign's check (scripts/beam_campaign.py: thousands of these) on a few of each family: a
    robot far from the others, on its target's column, on their rows, all far apart, symmetric starts
    with robots on the axis."""
    start, measure = case
    verdict = against_exact(start.robots, start.pattern, start.y_up, measure, seed=len(start.robots))
    assert verdict in ("", "none"), verdict


def test_a_start_that_is_already_the_pattern_costs_nothing():
    """Found by the campaign (spread, seed 383): two robots already in the pattern's shape. The engine
    calls it formed before anyone acts, and so does the exact worst (0 moves); the beam ran the
    algorithm on and found 6."""
    case = generate("spread", 383, far=12)
    assert against_exact(case.robots, case.pattern, case.y_up, "moves", seed=383) == ""
    assert beam(ALGORITHM, case.robots, case.pattern, case.y_up, "moves", 64).value == 0
