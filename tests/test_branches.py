"""Time travel keeps a tree: whatever sequence of steps from the past, Backs and entries, every line
ever left is still listed and re-enters to exactly its steps (generated walks through the tree)."""

from __future__ import annotations

import random

import pytest

from apf_viz.workbench.branches import Branches
from apf_viz.workbench.session import Session

START = [(0, 0), (0, 2), (1, 0), (1, 3), (3, 1)]
PATTERN = [(0, 0), (1, 0), (2, 0), (3, 0), (4, 0)]


def _line(s: Session) -> tuple:
    h = s.engine.history
    return tuple(h.steps.record(i) for i in range(h.length))


def _lines(branches: Branches, live: tuple) -> set[tuple]:
    """Every kept branch's whole line, from its path off the run's line."""
    out = set()
    for b in branches:
        at, steps = branches.path_to(b.number)
        out.add(live[:at] + tuple(steps))
    return out


@pytest.mark.parametrize("seed", range(12))
def test_no_line_is_ever_lost_in_generated_walks_through_the_tree(seed):
    rng = random.Random(seed)
    s = Session(START, PATTERN, y_up=[True] * 5, scheduler="manual")
    seen: set[tuple] = set()  # every line the run has stood on, at its end
    for _ in range(60):
        action = rng.random()
        if action < 0.55:  # a person's choice (it branches when it differs from the recorded step)
            robot = rng.randrange(5)
            if not s.engine.finished:
                s.run.step_robot(robot)
        elif action < 0.75:
            s.seek(rng.randrange(s.engine.history.length + 1))
        elif action < 0.85 and s.engine.step_index:
            s.back_cycle()
        elif len(s.run.branches):
            number = rng.choice([b.number for b in s.run.branches])
            at, steps = s.run.branches.path_to(number)
            wanted = _line(s)[:at] + tuple(steps)
            s.return_to_set_aside(number)
            # Entered: exactly that branch's steps (a branch whose steps were all taken again since lies
            # on the run's line already: the run's recorded future goes on past it).
            assert _line(s)[: len(wanted)] == wanted and s.engine.step_index <= len(wanted)
        seen.add(_line(s))
        live = _line(s)
        kept = _lines(s.run.branches, live) | {live}
        for line in seen:  # each line seen is a prefix of the run's line or of a kept one
            assert any(k[: len(line)] == line for k in kept), f"a line of {len(line)} steps was lost"
    assert s.run.branches.forgotten == 0
