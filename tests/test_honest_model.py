"""The model is honest: an algorithm gets only the local view, in its own frame."""

from __future__ import annotations

import subprocess
import sys

import pytest

from apf_viz.core.algorithm import Decision
from apf_viz.core.engine import Engine
from apf_viz.core.frames import move_to_global, to_local
from apf_viz.core.grid import Direction
from apf_viz.core.view import Seen, Snapshot


class Spy:
    """Records every argument it is given, and decides by hashing the view (any function would do)."""

    name = "spy"
    lights = ("off", "terminal1", "done")

    def __init__(self) -> None:
        self.calls: list[tuple] = []

    def decide(self, view, pattern) -> Decision:
        self.calls.append((view, pattern))
        below = sum(1 for s in view.robots if s.dy < 0)
        move = Direction.UP if below % 2 else (Direction.LEFT if view.robots else None)
        return Decision("terminal1" if below else "done", move, f"{below} below")


START = [(0, 0), (2, 1), (3, -2), (5, 0), (1, 4)]
PATTERN = [(x, 0) for x in range(5)]  # not the start: a start that is the pattern is formed before any Look


def _views_and_decisions(points, y_up):
    spy = Spy()
    engine = Engine(points, PATTERN, spy, y_up=y_up)
    out = []
    for r in range(len(points)):
        engine.step([r])  # Look
        engine.step([r])  # Compute
        out.append((engine.state.snapshot[r], engine.state.pending[r], engine.history.events()[-1].move))
    return out, spy


def test_same_local_view_under_two_placements_gives_the_same_decision():
    """Translate the whole configuration and mirror it in y while flipping every robot's y-axis:
    every robot's view is then identical, and so must be every decision (and the local move)."""
    a, _ = _views_and_decisions(START, [True, False, True, True, False])
    moved = [(x + 17, -y - 40) for x, y in START]
    b, _ = _views_and_decisions(moved, [False, True, False, False, True])
    for (view_a, dec_a, gmove_a), (view_b, dec_b, gmove_b) in zip(a, b, strict=True):
        assert view_a == view_b
        assert dec_a == dec_b
        # The same local move is a mirrored global move.
        assert gmove_b == move_to_global(gmove_a, False)


def test_the_algorithm_receives_nothing_but_a_snapshot_and_the_pattern():
    _, spy = _views_and_decisions(START, [True] * 5)
    assert spy.calls
    for view, pattern in spy.calls:
        assert type(view) is Snapshot
        assert set(Snapshot.__slots__) == {"light", "_robots", "_columns"}
        # Its arrays are the same robots, in the same order, with lights named from the algorithm's own.
        c = view.columns
        assert c.dx.tolist() == [s.dx for s in view.robots] and c.dy.tolist() == [s.dy for s in view.robots]
        assert [c.palette[i] for i in c.code.tolist()] == [s.light for s in view.robots]
        assert set(c.palette) <= set(Spy.lights)
        assert all(type(s) is Seen and set(s._fields) == {"dx", "dy", "light"} for s in view.robots)
        assert all(isinstance(s.dx, int) and isinstance(s.dy, int) for s in view.robots)
        assert pattern == tuple(PATTERN)
        # The robot itself is the origin: it never appears in its own view.
        assert all((s.dx, s.dy) != (0, 0) for s in view.robots)


def test_view_order_carries_no_identity():
    """Renumbering the robots changes no view: robot 0 of A and robot 2 of B stand on the same point."""
    perm = [START[i] for i in (4, 2, 0, 3, 1)]
    a = Engine(START, PATTERN, Spy())
    b = Engine(perm, PATTERN, Spy())
    assert a.look(0) == b.look(2)
    a.step([0])
    b.step([2])
    assert a.state.snapshot[0] == b.state.snapshot[2]


def test_a_flipped_robot_sees_y_mirrored_and_its_up_is_global_down():
    assert to_local((2, 3), y_up=False) == (2, -3)
    assert move_to_global(Direction.UP, False) is Direction.DOWN
    assert move_to_global(Direction.LEFT, False) is Direction.LEFT
    assert move_to_global(None, False) is None


@pytest.mark.parametrize("module", ["apf_viz.core", "apf_viz.algorithms", "apf_viz.cli"])
def test_the_core_never_imports_viser(module):
    code = f"import sys, {module}; import apf_viz.core.run; sys.exit('viser' in sys.modules)"
    assert subprocess.run([sys.executable, "-c", code]).returncode == 0


def test_a_snapshot_made_as_arrays_equals_the_same_snapshot_made_as_tuples():
    import pickle

    import numpy as np

    from apf_viz.core.view import Columns

    robots = (Seen(-2, 1, "done"), Seen(-2, 3, "off"), Seen(0, -1, "leader"), Seen(4, 0, "off"))
    palette = ("off", "terminal1", "leader", "done")
    columns = Columns(
        np.array([-2, -2, 0, 4]), np.array([1, 3, -1, 0]), np.array([3, 0, 2, 0], dtype=np.uint8), palette
    )
    a, b = Snapshot("off", robots), Snapshot("off", columns=columns)
    assert len(b) == 4 and b.lights() == a.lights() == {"done", "off", "leader"}
    assert a == b and hash(a) == hash(b) and b.robots == robots  # one memo entry for both
    assert a.columns.showing("leader").tolist() == [False, False, True, False]
    assert not a.columns.showing("call").any()  # a light nobody shows
    assert Snapshot("done", robots) != b
    assert pickle.loads(pickle.dumps(b)) == a


def test_ranges_of_a_snapshot_read_the_same_off_arrays_and_off_tuples():
    """The rules that scan part of a large view (a vertical line, the left half) read it by ranges; a
    snapshot made as arrays answers them without becoming tuples, and exactly as the tuples would."""
    import numpy as np

    from apf_viz.core.view import Columns

    rng = np.random.default_rng(5)
    cells = sorted({(int(x), int(y)) for x, y in rng.integers(-30, 30, size=(300, 2))} - {(0, 0)})
    names = ("off", "leader", "done")
    lights = [names[i] for i in rng.integers(0, 3, size=len(cells))]
    robots = tuple(Seen(x, y, light) for (x, y), light in zip(cells, lights, strict=True))
    columns = Columns(
        np.array([c[0] for c in cells]),
        np.array([c[1] for c in cells]),
        np.array([names.index(s) for s in lights], dtype=np.uint8),
        names,
    )
    a, b = Snapshot("off", robots), Snapshot("off", columns=columns)
    for dx in (-31, -30, -3, 0, 1, 7, 29, 30):
        for lo in (0, 5, 100):
            i = a.column_start(dx, lo)
            assert b.column_start(dx, lo) == i
            assert all(s.dx >= dx for s in robots[i:]) and all(s.dx < dx for s in robots[lo:i])
    assert [b.dx_at(i) for i in (0, 17, len(cells) - 1)] == [robots[i].dx for i in (0, 17, len(cells) - 1)]
    assert b.between(3, 40) == robots[3:40] and b.between(50, 50) == ()
    assert list(b.iter_between(2, 71)) == list(robots[2:71])  # across several chunks
    assert [b.count(light) for light in (*names, "call")] == [lights.count(x) for x in (*names, "call")]
    assert b._robots is None  # none of it made the whole tuple
