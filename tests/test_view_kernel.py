"""The compiled view build (core/view_kernel.py) gives exactly the numpy build's view, and a run with it
is the same run, event for event, as a run without it."""

from __future__ import annotations

import math
import random
import sys

import numba  # noqa: F401  (the test extra installs it: the compiled path is tested, not skipped)
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from apf_viz.algorithms.apf_opaque_grid.audit import random_pattern, random_solvable_start
from apf_viz.core import view_kernel, visibility
from apf_viz.core.engine import Engine
from apf_viz.core.run import advance
from apf_viz.core.schedulers import make_scheduler
from apf_viz.core.visibility import Views
from tests.oracle import visible_by_lattice_walk
from tests.test_fast_forward import engine as budgeted_engine

LIGHTS = tuple("abcdefghijkl")  # codes up to 11: the bits of `present` beyond a byte


def numpy_view(positions, lights, y_up, r, monkeypatch):
    """Robot r's view as the numpy build makes it (no kernel)."""
    with monkeypatch.context() as m:
        m.setattr(visibility, "compiled", lambda: None)
        views = Views(positions.copy(), list(lights), y_up, LIGHTS)
    robots, ids = views.view(r)
    return ids, robots.dx.tolist(), robots.dy.tolist(), robots.code.tolist()


def extent(positions) -> int:
    """The bound on every offset that Views passes the kernel: the robots' extent, the tightest."""
    return int(np.ptp(positions, axis=0).max())


def kernel_view(kernel, positions, lights, y_up, r):
    codes = np.array([LIGHTS.index(x) for x in lights], dtype=np.uint8)
    ids, sx, sy, dx, ly, code, present = kernel(
        positions, r, 1 if y_up[r] else -1, codes, extent(positions), *view_kernel.new_tables(len(lights))
    )
    assert present == sum(1 << c for c in set(code.tolist()))
    assert (sx == positions[ids, 0] - positions[r, 0]).all()
    assert (sy == positions[ids, 1] - positions[r, 1]).all()
    return tuple(ids.tolist()), dx.tolist(), ly.tolist(), code.tolist()


@st.composite
def configurations(draw):
    # Offsets within DIRECT_SPAN (the direction table), across it (127, 128) and beyond (the hash table).
    scale = draw(st.sampled_from([3, 8, 40, 127, 128, 200, 5000, view_kernel.KERNEL_SPAN_LIMIT // 2 - 1]))
    pts = draw(
        st.lists(
            st.tuples(st.integers(-scale, scale), st.integers(-scale, scale)),
            min_size=1,
            max_size=40,
            unique=True,
        )
    )
    k = len(pts)
    y_up = draw(st.lists(st.booleans(), min_size=k, max_size=k))
    lights = draw(st.lists(st.sampled_from(LIGHTS), min_size=k, max_size=k))
    r = draw(st.integers(0, k - 1))
    return np.array(pts, dtype=np.int64).reshape(k, 2), lights, y_up, r


@pytest.mark.parametrize("compiled", [False, True], ids=["python", "numba"])
@settings(max_examples=300, deadline=None)
@given(configurations())
def test_the_kernel_builds_the_numpy_view(compiled, configuration):
    """Both the compiled kernel and the same code run as plain Python (so that the kernel's logic is
    tested where numba is missing too) equal the numpy build, and its robots are the oracle's."""
    positions, lights, y_up, r = configuration
    kernel = view_kernel.compiled() if compiled else view_kernel.build_view
    assert kernel is not None
    mp = pytest.MonkeyPatch()
    try:
        expected = numpy_view(positions, lights, y_up, r, mp)
    finally:
        mp.undo()
    got = kernel_view(kernel, positions, lights, y_up, r)
    assert got == expected
    if np.abs(positions).max() <= 40:
        assert got[0] == tuple(visible_by_lattice_walk([tuple(p) for p in positions.tolist()], r))


def test_work_tables_used_again_by_every_observer_give_each_the_view_of_fresh_ones():
    """The direction table is never cleared (an entry counts for the call its stamp names): one set of
    tables used for every observer of crowds of several sizes (tables of several widths), in turn, builds
    the views fresh ones do."""
    kernel = view_kernel.compiled()
    rng = random.Random(8)
    tables = view_kernel.new_tables(120)
    for side in (6, 12, 40, 90, 200, 12):
        pts = rng.sample([(x, y) for x in range(side) for y in range(side)], min(120, side * side // 2))
        positions = np.array(pts, dtype=np.int64)
        codes = np.array([rng.randrange(len(LIGHTS)) for _ in pts], dtype=np.uint8)
        reach = extent(positions)
        for r in range(len(pts)):
            flip = rng.choice((1, -1))
            reused = kernel(positions, r, flip, codes, reach, *tables)
            fresh = kernel(positions, r, flip, codes, reach, *view_kernel.new_tables(len(pts)))
            assert all(np.array_equal(a, b) for a, b in zip(reused[:6], fresh[:6], strict=True))
            assert reused[6] == fresh[6]


def test_lines_of_sight_in_a_crowd():
    """Robots on rows, columns and diagonals through the observer: only the nearest of each is seen."""
    pts = [(x, y) for x in range(-6, 7) for y in range(-6, 7)]
    positions = np.array(pts, dtype=np.int64)
    r = pts.index((0, 0))
    lights = [LIGHTS[i % len(LIGHTS)] for i in range(len(pts))]
    ids, dx, ly, code = kernel_view(view_kernel.compiled(), positions, lights, [False] * len(pts), r)
    assert ids == tuple(visible_by_lattice_walk(pts, r))
    assert len(ids) == sum(math.gcd(x, y) == 1 for x, y in pts) == 96  # the primitive directions
    seen = list(zip(dx, ly, strict=True))
    assert (1, 0) in seen and (2, 0) not in seen
    assert seen == sorted(seen)


def test_the_environment_turns_the_kernel_off(monkeypatch):
    monkeypatch.setenv("APF_VIZ_KERNELS", "0")
    assert view_kernel.compiled() is None
    monkeypatch.setenv("APF_VIZ_KERNELS", "1")
    assert view_kernel.compiled() is not None


def test_without_numba_views_are_built_with_numpy(monkeypatch):
    monkeypatch.setitem(sys.modules, "numba", None)  # as if it were not installed
    assert view_kernel.compiled() is None
    positions = np.array([(i, i % 3) for i in range(view_kernel.KERNEL_MIN_ROBOTS)], dtype=np.int64)
    views = Views(positions, ["a"] * len(positions), [True] * len(positions))
    assert views._kernel is None
    assert views.view(0)[1] == tuple(visible_by_lattice_walk([tuple(p) for p in positions.tolist()], 0))


def test_small_runs_do_not_use_the_kernel():
    positions = np.array([(i, 0) for i in range(view_kernel.KERNEL_MIN_ROBOTS - 1)], dtype=np.int64)
    assert Views(positions, ["a"] * len(positions), [True] * len(positions))._kernel is None
    positions = np.array([(i, 0) for i in range(view_kernel.KERNEL_MIN_ROBOTS)], dtype=np.int64)
    assert Views(positions, ["a"] * len(positions), [True] * len(positions))._kernel is not None


def run(k: int, seed: int, scheduler: str, kernel: bool, monkeypatch, primed: bool = True) -> Engine:
    rng = random.Random(k * 1000 + seed)
    start = random_solvable_start(k, rng)
    case = (start, random_pattern(k, rng), [rng.random() < 0.5 for _ in range(k)])
    with monkeypatch.context() as m:
        if not kernel:
            m.setattr(visibility, "compiled", lambda: None)
        engine = budgeted_engine(case, True)
    assert (engine._views._kernel is not None) == kernel
    with monkeypatch.context() as m:
        if not primed:  # every Look's bits packed from its tuple
            m.setattr(visibility, "prime_seen", lambda seen, bits: None)
        advance(engine, make_scheduler(scheduler), seed)
    return engine


@pytest.mark.parametrize(("k", "seed", "scheduler"), [(60, 1, "async"), (50, 2, "stale-first")])
def test_a_run_with_the_kernel_is_the_same_run(k, seed, scheduler, monkeypatch):
    """With the kernel, without it, and without the bits of a Look made from the build's array
    (history.prime_seen): the same steps, recorded the same."""
    runs = [
        run(k, seed, scheduler, True, monkeypatch),
        run(k, seed, scheduler, False, monkeypatch),
        run(k, seed, scheduler, True, monkeypatch, primed=False),
    ]
    first = runs[0]
    packed = [first.history.packed(i) for i in range(first.history.length)]
    assert sum(1 for step in packed for e in step[2] if e[2]) > 1000  # many Looks, their bits compared
    for other in runs[1:]:
        assert other.outcome == first.outcome == "formed"
        assert (other.state.steps, other.state.moves) == (first.state.steps, first.state.moves)
        assert [other.history.packed(i) for i in range(other.history.length)] == packed
        assert (other.state.positions == first.state.positions).all()


def test_a_cache_numba_cannot_write_compiles_without_one(monkeypatch):
    """Where numba has nowhere to keep its cache (a read-only install, no writable home) it raises on
    ``cache=True``; the kernel is then compiled in each process instead of refused."""
    import numba as real

    calls = []

    def njit(**options):
        calls.append(options)
        if options.get("cache"):
            raise RuntimeError("cannot cache function: no locator available")
        return real.njit(**options)

    class NoCache:
        pass

    fake = NoCache()
    fake.njit = njit
    monkeypatch.setattr(view_kernel, "_counting_pass", view_kernel._counting_pass)
    monkeypatch.setattr(view_kernel, "_order_by_offset", view_kernel._order_by_offset)
    kernel = view_kernel._compile.__wrapped__(fake)
    assert calls[0].get("cache") and not any(c.get("cache") for c in calls[1:])
    positions = np.array([(i, i % 3) for i in range(10)], dtype=np.int64)
    got = kernel_view(kernel, positions, ["a"] * 10, [True] * 10, 0)
    assert got[0] == tuple(visible_by_lattice_walk([tuple(p) for p in positions.tolist()], 0))
