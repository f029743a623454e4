"""How long a run may go on: a budget that grows with the run, not a fixed event count.

The paper bounds the moves by O(kD), D = max(m, n, M, N, k) (m × n and M × N: the enclosing rectangles
of the start and of the pattern). We measure moves/(k·D) between 1.0 and 2.0 (docs/PERFORMANCE.md); the
budget allows ``MOVES_PER_KD`` = 50 times k·D, far above both, so a normal run never meets it and a run
that does is reported as ``limit``. Events are budgeted per move: with no-op activations skipped a move
costs about three events (a Look, a Compute, the Move) plus the light changes around it; with every
activation kept (``--all-activations``) each move also pays about one no-op cycle of every robot.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

from apf_viz.core.grid import Point

MOVES_PER_KD = 50
MAX_RECORDED = 4_000_000
"""The most steps a run holds in memory (a fast-forwarded walk is one, however long): a run whose robots
walk far while the adversary interleaves them records a step per event, so without this bound its memory
grows with the distance. The worst measured at this cap: 1.9 GB resident (docs/PERFORMANCE.md); it lets the
largest run measured, k = 1,000 to formed (3.0 million steps, 1.7 GiB), finish."""
EVENTS_PER_MOVE = 20  # skipping: ~3 measured; light changes without a move come on top
EVENTS_PER_MOVE_PER_ROBOT = 4  # all activations: ~3 per robot per move measured (one no-op cycle)


class Budget(NamedTuple):
    """A run's caps: past either it ends as ``limit`` (:func:`run_budget` gives the default)."""

    max_moves: int
    max_events: int


def paper_D(robots: Sequence[Point], pattern: Sequence[Point]) -> int:
    """D = max(m, n, M, N, k) of the paper."""

    def extent(points: Sequence[Point]) -> tuple[int, int]:
        xs, ys = [p[0] for p in points], [p[1] for p in points]
        return max(xs) - min(xs) + 1, max(ys) - min(ys) + 1

    return max(*extent(robots), *extent(pattern), len(robots))


def run_budget(robots: Sequence[Point], pattern: Sequence[Point], skip_noops: bool = True) -> Budget:
    """The default stop of a run from ``robots`` to ``pattern``."""
    k = len(robots)
    moves = MOVES_PER_KD * k * paper_D(robots, pattern)
    per_move = EVENTS_PER_MOVE + (0 if skip_noops else EVENTS_PER_MOVE_PER_ROBOT * k)
    return Budget(moves, moves * per_move)
