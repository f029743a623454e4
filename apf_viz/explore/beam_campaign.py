"""The beam over the adversary's choices (explore/beam.py) checked against the exact worst (``check
--worst``) on one start: the check of tests/test_beam.py, and of scripts/beam_campaign.py, which runs it
on thousands of starts of the adversarial families (core/adversarial_starts.py)."""

from __future__ import annotations

from apf_viz.algorithms import get_algorithm
from apf_viz.core.engine import Engine
from apf_viz.explore.beam import beam
from apf_viz.explore.worst import Measure, worst


def against_exact(
    robots, pattern, y_up, measure: Measure, seed: int, algorithm: str = "apf-opaque-grid"
) -> str:
    """'' if a beam never cut equals the exact worst, a narrow one (width 2–8) does not
    exceed it and both paths form in the engine at their cost; else what disagreed; 'none' where the
    start has no maximum (a failure of the algorithm, a cycle, or the state budget)."""
    exact = worst(get_algorithm(algorithm), robots, pattern, [y_up], measure, max_states=300_000)
    if exact.value is None:
        return "none"
    whole = beam(algorithm, robots, pattern, y_up, measure, 10**6)
    narrow = beam(algorithm, robots, pattern, y_up, measure, 2 + seed % 7, seed)
    if whole.cut or whole.value != exact.value:
        return f"the whole beam found {whole.value} (cut: {whole.cut}), the exact worst is {exact.value}"
    if narrow.value is None or narrow.value > exact.value:
        return f"a narrow beam found {narrow.value}, more than the exact worst {exact.value}"
    for found in (whole, narrow):
        e = Engine(robots, pattern, get_algorithm(algorithm), y_up=list(y_up))
        for group in found.schedule:
            e.step(group)
        cost = e.state.moves if measure == "moves" else e.state.events
        if e.outcome != "formed" or cost != found.value:
            return (
                f"a beam's path replays to {e.outcome} with {cost} {measure}, not formed with {found.value}"
            )
    return ""
