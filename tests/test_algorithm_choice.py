"""The algorithm as a person picks it (workbench/algorithm_choice.py): names and light merges in words."""

from __future__ import annotations

from apf_viz.algorithms import ALGORITHMS, get_algorithm
from apf_viz.workbench.algorithm_choice import NO_MERGE, algorithm_names, light_merges, merge_of, with_merge


def test_every_merge_offered_round_trips_through_its_algorithm_name():
    base = get_algorithm("apf-opaque-grid")
    choices = light_merges(base)
    assert choices[0] == NO_MERGE and len(choices) == 1 + len(base.lights) * (len(base.lights) - 1)
    for choice in choices:
        name = with_merge("apf-opaque-grid", choice)
        assert merge_of(name) == choice
        merged = get_algorithm(name)  # the registry builds it
        assert light_merges(merged) == choices  # offered from the unmerged lights
        assert with_merge(name, NO_MERGE) == "apf-opaque-grid"
    assert merge_of("apf-opaque-grid+merge(leader1=decider)") == "decider shown as leader1"


def test_the_names_are_the_registrys_and_a_variant_is_kept_last():
    assert algorithm_names("apf-opaque-grid") == tuple(ALGORITHMS)
    variant = "apf-opaque-grid@G1,G2"
    assert algorithm_names(variant, ["mine", "pkg.mod:Thing"]) == (*ALGORITHMS, "mine", variant)
