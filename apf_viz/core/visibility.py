"""Every robot's view of the current configuration, kept up to date move by move.

A Look needs, in the observer's own frame, the offset and light of each robot it sees: the nearest robot
along each primitive direction (paper §2, *Visibility*; :mod:`apf_viz.core.grid`). Recomputing that per
Look costs a sort of k offsets and k new tuples. But between two Looks usually one robot has moved, and
a move changes an observer's view in at most four places: the mover leaves one direction (the next robot
along it, if any, comes into sight) and enters another (hiding the robot that was nearest there, if the
mover is now nearer). :class:`Views` keeps, per observer, the nearest robot of every direction and the
view's entries sorted by offset, and patches them on each move or light change; a Look then costs a
``tuple()`` of a list, and identical views share their ``Seen`` objects. A view built and read before
any patch is handed over as arrays (:class:`~apf_viz.core.view.Columns`): the entries are made from them
only if a patch comes first.

An observer's index is built on its first Look (one sort, :func:`~apf_viz.core.grid.nearest_per_direction`)
and dropped when the observer itself moves (everything it sees shifts), so robots that never look cost
nothing. ``tests/test_visibility.py`` checks every patched view against a from-scratch one.
"""

from __future__ import annotations

from bisect import bisect_left, insort
from collections.abc import Iterator, Sequence
from typing import cast

import numpy as np

from apf_viz.core.grid import (
    PACKED_SPAN_LIMIT,
    TABLE_CENTRE,
    TABLE_SPAN,
    TABLE_WIDTH,
    Point,
    nearest_per_direction,
    table_scratch,
    visible_in_crowd,
)
from apf_viz.core.history import bits_of_sorted, prime_seen
from apf_viz.core.view import Columns, Seen
from apf_viz.core.view_kernel import KERNEL_MIN_ROBOTS, KERNEL_SPAN_LIMIT, compiled, new_tables

Direction2 = tuple[int, int]  # a primitive direction (dx, dy)/gcd, global frame


class Views:
    """Patched views of all robots.

    Args:
        positions: shape (k, 2), the engine's array; the engine writes moves into it, then calls
            :meth:`moved`.
        lights: the engine's list of lights; the engine changes an entry, then calls :meth:`relit`.
        y_up: per robot, whether its local +y is the global +y.
        palette: every light the algorithm may show (a view's arrays name lights by their index in it);
            the lights present at the start if None.
    """

    def __init__(
        self,
        positions: np.ndarray,
        lights: list[str],
        y_up: Sequence[bool],
        palette: Sequence[str] | None = None,
    ) -> None:
        self._P = positions
        self._lights = lights
        self._palette: tuple[str, ...] = tuple(palette) if palette is not None else tuple(sorted(set(lights)))
        self._code_of = np.array([self._code(light) for light in lights], dtype=np.uint8)
        self._flip = [1 if up else -1 for up in y_up]
        k = positions.shape[0]
        self.points: list[Point] = [(int(x), int(y)) for x, y in positions.tolist()]
        self.occupied: dict[Point, int] = {p: i for i, p in enumerate(self.points)}
        self._near: list[dict[Direction2, tuple[int, int]] | None] = [None] * k  # dir → (distance g, robot)
        # What a built view's index is made from, until a patch first needs it: most views are read once
        # (a robot about to move, or one the engine then watches another way) and never patched.
        self._raw: list[tuple[np.ndarray, np.ndarray, np.ndarray] | None] = [None] * k
        # A built view is either its arrays (``_columns``) or, once patched, its entries sorted by (dx, dy)
        # in the observer's frame (``_entries``); the other is None.
        self._columns: list[Columns | None] = [None] * k
        self._entries: list[list[Seen] | None] = [[] for _ in range(k)]
        # Sorted robot indices; None while the build's array (in ``_raw``) still says them.
        self._ids: list[list[int] | None] = [[] for _ in range(k)]
        # The view as read, and its indices once asked for (None until then).
        self._cached: list[tuple[Columns | tuple[Seen, ...], tuple[int, ...] | None] | None] = [None] * k
        self._built: set[int] = set()
        self._scratch: np.ndarray | None = None  # visible_in_crowd's work array, made on first use
        self._flat: np.ndarray | None = None  # x·TABLE_WIDTH + y per robot, with the scratch
        # The compiled build (view_kernel.py) and its work arrays, where numba is installed.
        self._kernel = compiled() if k >= KERNEL_MIN_ROBOTS else None
        self._tables = new_tables(k) if self._kernel is not None else None
        # A box every robot has stayed in (it only grows): while it is narrower than the tables, every
        # offset is in them.
        lo, hi = positions.min(axis=0).tolist(), positions.max(axis=0).tolist()
        self._reach = (lo[0], lo[1], hi[0], hi[1])
        # Robots whose view changed since the engine last drained this set (it re-decides only them).
        self.changed: set[int] = set()

    # ------------------------------------------------------------------ reading
    def view(self, r: int) -> tuple[Columns | tuple[Seen, ...], tuple[int, ...]]:
        """What robot r sees now: its robots sorted by offset in its own frame (as arrays if the view is
        fresh, else as entries), and their robots' indices (sorted). Unchanged views return the same
        objects."""
        robots = self.robots(r)
        cached = self._cached[r]
        assert cached is not None  # robots(r) made it
        if cached[1] is None:
            ids = self._ids[r]
            if ids is None:
                raw = self._raw[r]
                assert raw is not None  # a built view keeps its indices in one of the two
                ids = raw[2].tolist()
            cached = self._cached[r] = (robots, tuple(ids))
        return cast("tuple[Columns | tuple[Seen, ...], tuple[int, ...]]", cached)  # its indices now made

    def robots(self, r: int) -> Columns | tuple[Seen, ...]:
        """:meth:`view` without the indices: what a decision reads (the indices of 800 robots as a tuple
        cost a quarter of a crowd's view, and only a Look records them)."""
        cached = self._cached[r]
        if cached is None:
            if r not in self._built:
                self._build(r)
            entries = self._entries[r]
            columns = self._columns[r]
            robots: Columns | tuple[Seen, ...]
            if entries is None:
                assert columns is not None  # a built view is its arrays or its entries
                robots = columns
            else:
                robots = tuple(entries)
            cached = self._cached[r] = (robots, None)
        return cached[0]

    def prime_seen_bits(self, r: int, ids: tuple[int, ...]) -> None:
        """Robot r Looked and saw ``ids`` (from :meth:`view`): while its view is as built, the history's
        bits of them are made from the build's array (a few µs at k = 1,000) instead of from the tuple."""
        raw = self._raw[r]
        cached = self._cached[r]
        if raw is not None and cached is not None and cached[1] is ids:
            prime_seen(ids, bits_of_sorted(raw[2]))

    def seen(self, r: int) -> tuple[tuple[Seen, ...], tuple[int, ...]]:
        """:meth:`view` with the robots as :class:`~apf_viz.core.view.Seen` tuples."""
        robots, ids = self.view(r)
        return (robots if isinstance(robots, tuple) else tuple(robots.entries())), ids

    def _code(self, light: str) -> int:
        try:
            return self._palette.index(light)
        except ValueError:  # a light the palette lacks (no palette given): named from now on
            self._palette = (*self._palette, light)
            return len(self._palette) - 1

    def _build(self, r: int) -> None:
        P = self._P
        x0, y0, x1, y1 = self._reach
        reach = max(x1 - x0, y1 - y0)  # no offset is larger
        if self._kernel is not None and self._tables is not None and reach < KERNEL_SPAN_LIMIT:
            order, sx, sy, dx, ly, codes, present = self._kernel(
                P, r, self._flip[r], self._code_of, reach, *self._tables
            )
            columns = Columns(dx, ly, codes, self._palette, int(present) if present >= 0 else None)
            self._set_built(r, order, sx, sy, columns)
            return
        if x1 - x0 < TABLE_SPAN and y1 - y0 < TABLE_SPAN:  # a crowd: every offset is in the tables
            if self._scratch is None or self._flat is None:
                self._scratch = table_scratch()
                self._flat = P[:, 0] * TABLE_WIDTH + P[:, 1]
            # The table index of r's offset to each robot, from the robots' own flat indices.
            flat = self._flat
            at = flat - (int(flat[r]) - TABLE_CENTRE)
            order = visible_in_crowd(at, r, self._scratch)  # sorted by index
            seen = P[order] - P[r]
            span = TABLE_SPAN
        else:
            # The reach box bounds every offset (no pass over them to find the largest).
            span = max(x1 - x0, y1 - y0) + 1
            offsets = P - P[r]
            order = nearest_per_direction(offsets, r, span)
            order.sort()
            seen = offsets[order]
        sx, sy = seen[:, 0], seen[:, 1]
        ly = sy if self._flip[r] == 1 else -sy
        # The view's order: by dx, then dy in r's own frame; one packed key sorts fastest where it cannot
        # overflow (|sx|, |ly| < span: |key| < (2·span + 1)·span + span).
        packed = span < PACKED_SPAN_LIMIT
        by_offset = (sx * (2 * span + 1) + ly).argsort() if packed else np.lexsort((ly, sx))
        codes = self._code_of[order[by_offset]]
        self._set_built(r, order, sx, sy, Columns(sx[by_offset], ly[by_offset], codes, self._palette))

    def _set_built(self, r: int, order: np.ndarray, sx: np.ndarray, sy: np.ndarray, columns: Columns) -> None:
        """Robot r's view is built: the robots it sees (increasing), their global offsets, its arrays."""
        self._raw[r] = (sx, sy, order)
        self._near[r] = None
        self._columns[r] = columns
        self._entries[r] = None
        self._ids[r] = None  # made from ``order`` when a patch first needs it (most views are never patched)
        self._built.add(r)

    def _track(self, m: int) -> None:
        """Robot m moved (``points`` holds its new point): its flat index and the reach box follow."""
        x, y = self.points[m]
        if self._flat is not None:
            self._flat[m] = x * TABLE_WIDTH + y
        x0, y0, x1, y1 = self._reach
        self._reach = (min(x0, x), min(y0, y), max(x1, x), max(y1, y))

    def _entries_of(self, r: int) -> list[Seen]:
        """Robot r's entries (its view is built), made from its arrays when a patch first needs them."""
        entries = self._entries[r]
        if entries is None:
            columns = self._columns[r]
            assert columns is not None  # a built view is its arrays or its entries
            entries = self._entries[r] = columns.entries()
            self._columns[r] = None
        return entries

    def _index(self, r: int) -> dict[Direction2, tuple[int, int]]:
        """Robot r's nearest robot per primitive direction (r's view is built)."""
        near = self._near[r]
        if near is None:
            raw = self._raw[r]
            assert raw is not None  # kept while the view is built
            sx, sy, ids = raw
            g = np.gcd(sx, sy)
            near = self._near[r] = dict(
                zip(
                    zip((sx // g).tolist(), (sy // g).tolist(), strict=True),
                    zip(g.tolist(), ids.tolist(), strict=True),
                    strict=True,
                )
            )
            self._ids[r] = ids.tolist()
            self._raw[r] = None
        return near

    def _ids_of(self, r: int) -> list[int]:
        """Robot r's sorted indices, once a patch needs them (:meth:`_index` made them)."""
        ids = self._ids[r]
        assert ids is not None
        return ids

    # ------------------------------------------------------------------ patching
    def moved(self, movers: Sequence[int], old: Sequence[Point]) -> None:
        """These robots moved simultaneously from ``old`` to their current rows of ``positions``."""
        if len(movers) == 1:
            self._moved_one(movers[0], old[0])
            return
        P = self._P
        occupied = self.occupied
        for p in old:
            del occupied[p]
        for m in movers:
            self.points[m] = (int(P[m, 0]), int(P[m, 1]))
            self._track(m)
        lo, hi = P.min(axis=0).tolist(), P.max(axis=0).tolist()
        for m in movers:
            self._forget(m)
        observers = list(self._built)  # the movers are not among them
        here = P[np.asarray(observers, dtype=np.intp)]
        # Phase A: every mover leaves its old point; walks along a vacated direction see only robots that
        # did not move (the movers' new points are not yet occupied).
        for m, (ox, oy) in zip(movers, old, strict=True):
            for r, d, g in _directions(observers, here, ox, oy):
                near = self._index(r)
                if near.get(d) != (g, m):
                    continue  # m was hidden from r: nothing r sees changes
                self._drop(r, m, g * d[0], g * d[1])
                nxt = self._walk(self.points[r], d, g, lo, hi, occupied)
                if nxt is None:
                    del near[d]
                else:
                    near[d] = nxt
                    self._add(r, nxt[1], nxt[0] * d[0], nxt[0] * d[1])
        for m in movers:
            occupied[self.points[m]] = m
        # Phase B: every mover enters its new point, hiding whoever it is now in front of.
        for m in movers:
            nx, ny = P[m].tolist()
            for r, d, g in _directions(observers, here, nx, ny):
                near = self._index(r)
                cur = near.get(d)
                if cur is not None and cur[0] < g:
                    continue  # m is behind a robot r already sees
                if cur is not None:
                    self._drop(r, cur[1], cur[0] * d[0], cur[0] * d[1])
                near[d] = (g, m)
                self._add(r, m, g * d[0], g * d[1])

    def _moved_one(self, m: int, old: Point) -> None:
        """The ASYNC case of :meth:`moved`, in one pass per observer: walks along a vacated direction
        run in the final configuration (they may find m itself, if it moved along that direction), and a
        robot that stays in sight keeps its place in the sorted ids."""
        P = self._P
        new = self.points[m] = (int(P[m, 0]), int(P[m, 1]))
        self._track(m)
        occupied = self.occupied
        del occupied[old]
        occupied[new] = m
        self._forget(m)
        observers = list(self._built)
        if not observers:
            return
        lo, hi = P.min(axis=0).tolist(), P.max(axis=0).tolist()
        here = P[np.asarray(observers)]
        before = _directions(observers, here, old[0], old[1])
        after = _directions(observers, here, new[0], new[1])
        points, flips, nears = self.points, self._flip, self._near
        for (r, d0, g0), (_, d1, g1) in zip(before, after, strict=True):
            near = nears[r]
            if near is None:
                near = self._index(r)
            flip = flips[r]
            entries = self._entries_of(r)
            seen_before = near.get(d0) == (g0, m)
            if seen_before:
                del entries[bisect_left(entries, (g0 * d0[0], g0 * d0[1] * flip))]
                nxt = self._walk(points[r], d0, g0, lo, hi, occupied)
                if nxt is None:
                    del near[d0]
                else:
                    near[d0] = nxt
                    if nxt[1] != m:
                        self._add(r, nxt[1], nxt[0] * d0[0], nxt[0] * d0[1])
            cur = near.get(d1)
            if cur is not None and cur[1] == m:
                seen_after = True  # found by the walk above
            elif cur is None or g1 < cur[0]:
                if cur is not None:
                    self._drop(r, cur[1], cur[0] * d1[0], cur[0] * d1[1])
                near[d1] = (g1, m)
                seen_after = True
            else:
                seen_after = False
            if seen_after:
                insort(entries, Seen(g1 * d1[0], g1 * d1[1] * flip, self._lights[m]))
                if not seen_before:
                    insort(self._ids_of(r), m)
            elif seen_before:
                ids = self._ids_of(r)
                del ids[bisect_left(ids, m)]
            if seen_before or seen_after:
                self._cached[r] = None
                self.changed.add(r)

    def relit(self, m: int) -> None:
        """Robot m's light changed (the engine's ``lights`` list already holds the new one)."""
        light = self._lights[m]
        self._code_of[m] = self._code(light)
        observers = [r for r in self._built if r != m]
        if not observers:
            return
        mx, my = self._P[m].tolist()
        for r, d, g in _directions(observers, self._P[np.asarray(observers)], mx, my):
            if self._index(r).get(d) != (g, m):
                continue
            entries = self._entries_of(r)
            lx, ly = g * d[0], g * d[1] * self._flip[r]
            i = bisect_left(entries, (lx, ly))
            entries[i] = Seen(lx, ly, light)
            self._cached[r] = None
            self.changed.add(r)

    def release(self, r: int) -> None:
        """Stop keeping robot r's view (the engine watches r another way); it is rebuilt on r's next Look."""
        if r in self._built:
            self._built.discard(r)
            self._near[r] = self._raw[r] = None
            self._cached[r] = None
            self._entries[r] = []
            self._columns[r] = None
            self._ids[r] = []

    def _forget(self, m: int) -> None:
        """A robot that moved sees everything shifted: its view is rebuilt on its next Look."""
        if m in self._built:
            self.release(m)
            self.changed.add(m)

    def _drop(self, r: int, j: int, gx: int, gy: int) -> None:
        entries = self._entries_of(r)
        del entries[bisect_left(entries, (gx, gy * self._flip[r]))]
        ids = self._ids_of(r)
        del ids[bisect_left(ids, j)]
        self._cached[r] = None
        self.changed.add(r)

    def _add(self, r: int, j: int, gx: int, gy: int) -> None:
        insort(self._entries_of(r), Seen(gx, gy * self._flip[r], self._lights[j]))
        insort(self._ids_of(r), j)
        self._cached[r] = None
        self.changed.add(r)

    def _walk(
        self,
        start: Sequence[int],
        d: Direction2,
        g: int,
        lo: list[int],
        hi: list[int],
        occupied: dict[Point, int],
    ) -> tuple[int, int] | None:
        """The nearest robot along direction d from ``start`` beyond distance g, as (distance, robot).

        Walks the lattice points while that is shorter than a pass over the k robots; a long way across
        a sparse box (robots far apart) is one vectorised pass instead, so a move never costs more than
        O(k) per observer whatever the coordinates."""
        ddx, ddy = d
        t = g + 1
        x, y = start[0] + t * ddx, start[1] + t * ddy
        lox, loy = lo
        hix, hiy = hi
        left = min(_steps_inside(x, lox, hix, ddx), _steps_inside(y, loy, hiy, ddy))
        if left > len(occupied) + 16:
            return self._nearest_along(start, d, g, occupied)
        while lox <= x <= hix and loy <= y <= hiy:
            j = occupied.get((x, y))
            if j is not None:
                return t, j
            x += ddx
            y += ddy
            t += 1
        return None

    def _nearest_along(
        self, start: Sequence[int], d: Direction2, g: int, occupied: dict[Point, int]
    ) -> tuple[int, int] | None:
        """:meth:`_walk` as one pass over the robots: those whose primitive direction from ``start`` is d,
        beyond distance g, and that stand where ``occupied`` says (mid-way through simultaneous moves a
        mover's new point is not occupied yet). Gcds and quotients only: no product of coordinates, so
        nothing can overflow."""
        offsets = self._P - np.array(start, dtype=np.int64)
        ox, oy = offsets[:, 0], offsets[:, 1]
        dist = np.gcd(ox, oy)
        dist[dist == 0] = 1  # the observer itself: direction (0, 0), never d
        candidates = np.flatnonzero((ox // dist == d[0]) & (oy // dist == d[1]) & (dist > g))
        points = self.points
        for j in candidates[np.argsort(dist[candidates], kind="stable")].tolist():
            if occupied.get(points[j]) == j:
                return int(dist[j]), j
        return None


def _steps_inside(c: int, lo: int, hi: int, step: int) -> int:
    """How many more points of the walk c, c + step, ... stay within [lo, hi] on one axis."""
    if step > 0:
        return (hi - c) // step + 1
    if step < 0:
        return (c - lo) // -step + 1
    return 1 << 62 if lo <= c <= hi else 0


def _directions(
    observers: list[int], here: np.ndarray, px: int, py: int
) -> Iterator[tuple[int, tuple[int, int], int]]:
    """(observer, primitive direction towards (px, py), lattice distance g) for every observer."""
    ox = px - here[:, 0]
    oy = py - here[:, 1]
    g = np.gcd(ox, oy)
    g[g == 0] = 1  # no observer stands on the point (observers are never movers); a guard, not a case
    return zip(observers, zip((ox // g).tolist(), (oy // g).tolist(), strict=True), g.tolist(), strict=True)
