"""What fast-forward asks the watches: how many of a lone walker's next moves concern no watcher
(:meth:`QuietSteps.quiet_steps`), read along the walk's line (:class:`WalkPath`) off the other robots'
:class:`~apf_viz.core.watches.Watches`."""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np

from apf_viz.core.grid import Point
from apf_viz.core.watch_geometry import VECTOR_SPAN
from apf_viz.core.watches import Watches


class QuietSteps:
    """The walker's quiet moves, read off the watches of the other robots (``watches``)."""

    def __init__(self, watches: Watches) -> None:
        self.watches = watches

    def quiet_steps(self, r: int, start: Point, delta: Point, n: int) -> int:
        """How many of robot r's next moves, from ``start`` by ``delta`` (one lattice step along an axis),
        concern no watcher, up to n. A lower bound (0 when unsure): moving r straight to
        ``start + n′·delta`` at once then concerns nobody, as none of the n′ single moves would
        (:mod:`apf_viz.core.fast_forward`)."""
        ws = self.watches
        if not ws.count:
            return n
        if int(ws.bits[r]) & ws._watched:
            return 0  # a watched light is news wherever it comes into sight
        path = WalkPath(start, delta)
        mine = ws._followed.get(r, set())  # segments that follow the walker: taken along, not touched
        any_at = ws._any_at
        first = min(
            path.first_of(ws._watchers_at, n + 1),
            path.first_of((p for p in path.on_line(any_at) if not any_at[p] <= mine), n + 1),
        )  # the first point of the walk (0 … n) that some watched region contains
        for w, (boxes, longs) in ws._boxed.items():
            for box in boxes:
                first = min(first, path.first_in(path.box(box), n))
            wx, wy = int(ws._P[w, 0]), int(ws._P[w, 1])
            for ux, uy, g in longs:
                first = min(first, path.first_in(path.segment(wx, wy, ux, uy, g), n))
        quiet = first - 1  # the move onto that point, or off it (the start), touches it
        if mine:
            quiet = min(quiet, self._quiet_witness(r, mine, path, quiet))
        if ws._occupied:
            quiet = min(quiet, self._quiet_occupied(path, n))
        if ws._watched:
            quiet = min(quiet, self._quiet_reveals(r, path, n))
        return max(0, quiet)

    def _quiet_witness(self, r: int, mine: set[tuple[int, int]], path: WalkPath, n: int) -> int:
        """Moves during which every watcher following the walker keeps a witness in sight: another
        witness (whose segment the walk does not touch, see :meth:`quiet_steps`), or the walker itself,
        in sight and inside the watch's ``within``. (Within those moves the engine may drop and re-pick
        the walker's segment; the watcher's answer stays "same light, stay" either way.)"""
        ws = self.watches
        quiet = n
        P = ws._P
        touched: dict[int, set[int]] = {}  # watcher → its witnesses the walk touches
        for w, i in mine:
            touched.setdefault(w, set()).add(i)
        for w, used in touched.items():
            if ws._intact[w] - used:
                continue
            within = ws._within[w]
            if within is not None:
                lo, hi = path.box(within)
                if not lo <= 1 <= hi:
                    return 0
                quiet = min(quiet, hi)
            quiet = min(quiet, path.first_hidden(P, w, r, quiet + 1) - 1)
        return max(quiet, 0)

    def _quiet_occupied(self, path: WalkPath, n: int) -> int:
        """Moves before the walker is the last robot to leave some watch's occupied boxes."""
        ws = self.watches
        quiet = n
        x, y = path.x, path.y  # where the walker stands
        for boxes, counts in ws._occupied.values():
            # Another robot keeps a box occupied whatever the walker does: a box counting two robots, or one
            # that is not the walker. (Tested before the spans: most watches are skipped here.)
            if any(
                count > 1 or (count and not (x0 <= x <= x1 and y0 <= y <= y1))
                for count, (x0, x1, y0, y1) in zip(counts, boxes, strict=True)
            ):
                continue
            spans = [path.box(box) for box in boxes]
            for t in [1] + [hi + 1 for _, hi in spans]:
                if 1 <= t <= quiet and not any(lo <= t <= hi for lo, hi in spans):
                    quiet = t - 1
        return quiet

    def _quiet_reveals(self, r: int, path: WalkPath, n: int) -> int:
        """Moves before the walker leaves a point between a robot of a watched light and a watcher of
        that light (it may be revealed to the watcher then)."""
        ws = self.watches
        quiet = n
        P = ws._P
        for q in (ws.bits & ws._watched).nonzero()[0].tolist():
            watchers = ws.active & ((ws._mask & ws.bits[q]) != 0)
            watchers[q] = False
            if watchers.any():
                quiet = min(quiet, path.first_between(P[q], P[watchers], n - 1))
        return quiet


class WalkPath:
    """The points start + t·delta of a walk along an axis, as their t: a point is (along, across), the
    walk being across = 0."""

    def __init__(self, start: Point, delta: Point) -> None:
        self.x, self.y = start
        self.ex, self.ey = delta

    def _rel(self, px: int, py: int) -> tuple[int, int]:
        if self.ey == 0:
            return (px - self.x) * self.ex, py - self.y
        return (py - self.y) * self.ey, px - self.x

    def box(self, box: tuple[int, int, int, int]) -> tuple[int, int]:
        """The t of the walk's line inside a closed box (global bounds), as (lo, hi); lo > hi if none."""
        x0, x1, y0, y1 = box
        if self.ey == 0:
            if not y0 <= self.y <= y1:
                return 1, 0
            lo, hi = (x0 - self.x, x1 - self.x) if self.ex == 1 else (self.x - x1, self.x - x0)
        else:
            if not x0 <= self.x <= x1:
                return 1, 0
            lo, hi = (y0 - self.y, y1 - self.y) if self.ey == 1 else (self.y - y1, self.y - y0)
        return lo, hi

    def segment(self, wx: int, wy: int, ux: int, uy: int, g: int) -> tuple[int, int]:
        """The t of the walk's line on the segment w + s·(ux, uy), 1 ≤ s ≤ g."""
        a0, b0 = self._rel(wx, wy)
        a1, b1 = self._rel(wx + ux, wy + uy)
        da, db = a1 - a0, b1 - b0
        if db == 0:
            if b0 != 0:
                return 1, 0
            ends = (a0 + da, a0 + g * da)
            return min(ends), max(ends)
        if b0 % db or not 1 <= -b0 // db <= g:
            return 1, 0
        t = a0 - b0 // db * da
        return t, t

    def between(self, q: Point, w: Point) -> tuple[int, int]:
        """The t of the walk's line strictly between q and w."""
        aq, bq = self._rel(*q)
        aw, bw = self._rel(*w)
        if bq == 0 and bw == 0:
            return min(aq, aw) + 1, max(aq, aw) - 1
        if bq * bw >= 0:
            return 1, 0  # both on one side (or one on the line: an end, not between)
        num, den = aq * (bw - bq) - (aw - aq) * bq, bw - bq  # a where the segment crosses b = 0
        if num % den:
            return 1, 0
        return num // den, num // den

    def first_between(self, q: np.ndarray, W: np.ndarray, n: int) -> int:
        """``min(first_in(between(q, w), n) for w in W)``: vectorised where the products below fit in
        int64 (offsets from the walk's start under 2^30), else in Python integers."""
        span = max(int(np.abs(W - (self.x, self.y)).max()), abs(int(q[0]) - self.x), abs(int(q[1]) - self.y))
        if span >= VECTOR_SPAN:
            qp = (int(q[0]), int(q[1]))
            return min(
                (self.first_in(self.between(qp, (int(x), int(y))), n) for x, y in W.tolist()), default=n + 2
            )
        if self.ey == 0:
            aq, bq = (int(q[0]) - self.x) * self.ex, int(q[1]) - self.y
            aw, bw = (W[:, 0] - self.x) * self.ex, W[:, 1] - self.y
        else:
            aq, bq = (int(q[1]) - self.y) * self.ey, int(q[0]) - self.x
            aw, bw = (W[:, 1] - self.y) * self.ey, W[:, 0] - self.x
        first = n + 2
        if bq == 0:  # q on the walk's line: the points strictly between q and the watchers on it
            on = bw == 0
            if on.any():
                lo = np.minimum(aw[on], aq) + 1
                hi = np.maximum(aw[on], aq) - 1
                lo = np.maximum(lo, 0)
                hit = lo[lo <= np.minimum(hi, n)]
                if hit.size:
                    first = int(hit.min())
            return first
        cross = bw * bq < 0  # on the other side: the segment crosses the line once
        if not cross.any():
            return first
        aw, bw = aw[cross], bw[cross]
        den = bw - bq
        num = aq * den - (aw - aq) * bq
        exact = num % den == 0
        t = num[exact] // den[exact]
        t = t[(t >= 0) & (t <= n)]
        return int(t.min()) if t.size else first

    def on_line(self, points: Iterable[Point]) -> list[Point]:
        """Those of these points on the walk's line (either way from its start)."""
        if self.ey == 0:
            y = self.y
            return [p for p in points if p[1] == y]
        x = self.x
        return [p for p in points if p[0] == x]

    def first_of(self, points: Iterable[Point], limit: int) -> int:
        """The least t (0 ≤ t < limit) of these points on the walk; ``limit`` if none is."""
        x, y, ex, ey = self.x, self.y, self.ex, self.ey
        if ey == 0:
            ts = [(px - x) * ex for px, py in points if py == y]
        else:
            ts = [(py - y) * ey for px, py in points if px == x]
        return min((t for t in ts if 0 <= t < limit), default=limit)

    def first_hidden(self, P: np.ndarray, w: int, r: int, limit: int) -> int:
        """The least t (1 ≤ t < limit) at which some robot (not r) stands between robot w and the
        walk's point; ``limit`` if none does. Vectorised where products of offsets fit in int64."""
        wx, wy = int(P[w, 0]), int(P[w, 1])
        span = int(np.abs(P - P[w]).max()) + abs(self.x - wx) + abs(self.y - wy)
        if span >= 1 << 31:
            points = [(int(x), int(y)) for x, y in P.tolist()]
            return min(
                (
                    self.first_in(self.behind((wx, wy), q), limit)
                    for i, q in enumerate(points)
                    if i not in (r, w)
                ),
                default=limit,
            )
        if self.ey == 0:
            a, b = (P[:, 0] - self.x) * self.ex, P[:, 1] - self.y
        else:
            a, b = (P[:, 1] - self.y) * self.ey, P[:, 0] - self.x
        aw, bw = int(a[w]), int(b[w])
        d = b - bw
        ok = (d != 0) & (bw * d < 0) & (np.abs(d) < abs(bw))  # the ray from w through q crosses the line
        ok[[r, w]] = False
        if not ok.any():
            return limit
        d, num = d[ok], aw * d[ok] - (a[ok] - aw) * bw  # …at a = num / d
        t = num[num % d == 0] // d[num % d == 0]
        t = t[(t >= 1) & (t < limit)]
        return int(t.min()) if t.size else limit

    def behind(self, w: Point, q: Point) -> tuple[int, int]:
        """The t of the walk's line that q hides from w (q strictly between w and the point)."""
        aw, bw = self._rel(*w)
        aq, bq = self._rel(*q)
        if bq == bw or bw * (bq - bw) >= 0 or abs(bq - bw) >= abs(bw):
            return 1, 0  # the ray from w through q runs parallel, away, or crosses the line before q
        num, den = aw * (bq - bw) - (aq - aw) * bw, bq - bw  # a where that ray crosses b = 0
        if num % den:
            return 1, 0
        return num // den, num // den

    @staticmethod
    def first_in(span: tuple[int, int], n: int) -> int:
        """The least t of ``span`` within 0 … n; n + 2 if none (beyond every bound a caller takes)."""
        lo, hi = span
        lo = max(lo, 0)
        return lo if lo <= min(hi, n) else n + 2
