"""Which idle robots a move or a light change concerns: the engine's side of a ``Watch``.

An idle robot whose decision on its current view is "same light, stay" need not be asked again until
something it depends on changes. Without a watch that is "anything in its view", so every observer of a
move is re-decided and every built view patched: O(k) Python work per move, most of a large run's time
(docs/PERFORMANCE.md). With a watch the robot's view is dropped, and per move or light change a few numpy
passes and dictionary look-ups find the few watches the event touches:

- a point of a box or a segment is vacated, entered or relit (regions are convex and contain their robot,
  so what the robot sees inside one depends on nothing outside it);
- a robot showing a watched light comes into sight: it moves to a point the watcher sees, it is
  revealed (the vacated point was the only robot between it and the watcher: the two nearest robots on
  either side of the vacated point along one line), or it takes the light while the watcher sees it;
- the last robot leaves the ``occupied`` boxes of a watch (a count per box, kept move by move: a robot
  walking about inside one costs a few numpy comparisons and wakes nobody).

The watches are kept in the global frame, so a test costs the same for every robot. Coordinates are far
below 2^62 (``COORD_LIMIT``), so the sentinel bounds never overflow; direction keys are packed only when
the configuration's span allows it, else every robot watching a light is asked again (exact, slower).
"""

from __future__ import annotations

from collections.abc import Container, Iterable, Mapping, Sequence
from math import gcd

import numpy as np

from apf_viz.core.algorithm import Box, Watch
from apf_viz.core.grid import PACKED_SPAN_LIMIT, Point, visible_from

BOXES = 2  # per robot; a watch with more regions is not registered (the robot stays fully observed)
SEGMENTS = 2
OCCUPIED = 2
FEW_REGIONS = 16  # up to this many robots with boxes or long segments, they are tested one by one
WALK = 32  # lattice points walked, looking for a robot, before one numpy pass over every robot
FEW_SHOWN = 8  # up to this many robots of watched lights, a reveal is looked for from each of them
SHORT = 64  # a segment of at most this many lattice steps is kept as its points
_BIG = 1 << 62
_VECTOR_SPAN = 1 << 30  # offsets below this: products of two fit in int64


def _lattice_points(x: int, y: int, dx: int, dy: int) -> list[Point]:
    """The lattice points of the segment from (x, y) to (x + dx, y + dy), without (x, y) itself: nothing
    moves onto a watching robot."""
    g = gcd(dx, dy)
    ux, uy = dx // g, dy // g
    return [(x + t * ux, y + t * uy) for t in range(1, g + 1)]


class Watches:
    """The registered watches of idle robots, and the robots an event concerns.

    Args:
        positions: the engine's (k, 2) array (read, never written).
        lights: the engine's list of lights (read).
        light_names: every light the algorithm may show (a watched light is a bit of this list).
        y_up: per robot, whether its local +y is the global +y.
    """

    def __init__(
        self,
        positions: np.ndarray,
        lights: list[str],
        light_names: Sequence[str],
        y_up: Sequence[bool],
        robot_at: Mapping[Point, int] | None = None,
    ) -> None:
        k = positions.shape[0]
        self._P = positions
        # Which robot stands where (the engine's own map, kept current by its views): any-of witnesses are
        # followed by robot, not by point.
        self._robot_at = (
            robot_at if robot_at is not None else {(x, y): i for i, (x, y) in enumerate(positions.tolist())}
        )
        # A box every robot has stayed in (it only grows): a walk that leaves it has nobody beyond.
        lo, hi = positions.min(axis=0).tolist(), positions.max(axis=0).tolist()
        self._reach: tuple[int, int, int, int] = (lo[0], lo[1], hi[0], hi[1])
        self._bit = {name: 1 << i for i, name in enumerate(light_names)}
        self._flip = [1 if up else -1 for up in y_up]
        self.bits = np.array([self._bit.get(light, 0) for light in lights], dtype=np.int64)
        self.active = np.zeros(k, dtype=bool)
        # Unused box slots are empty (x0 > x1); unused segment slots have length g = 0, matching no point.
        self._bx0 = np.full((k, BOXES), _BIG, dtype=np.int64)
        self._bx1 = np.full((k, BOXES), -_BIG, dtype=np.int64)
        self._by0 = np.full((k, BOXES), _BIG, dtype=np.int64)
        self._by1 = np.full((k, BOXES), -_BIG, dtype=np.int64)
        # Segments of at most SHORT lattice steps are kept point by point (an event looks its points up);
        # longer ones as a direction and a length, tested in one numpy pass.
        self._watchers_at: dict[Point, set[int]] = {}
        self._points_of: list[list[Point]] = [[] for _ in range(k)]
        self._sdx = np.zeros((k, SEGMENTS), dtype=np.int64)  # primitive direction, global frame
        self._sdy = np.zeros((k, SEGMENTS), dtype=np.int64)
        self._sg = np.zeros((k, SEGMENTS), dtype=np.int64)  # length in lattice steps
        # Any-of segments (short ones only): point → (robot, segment) pairs; a robot is asked again when
        # every one of its any-of segments has been touched.
        self._any_at: dict[Point, set[tuple[int, int]]] = {}
        self._any_points: list[list[tuple[Point, int]]] = [[] for _ in range(k)]
        self._intact: list[set[int]] = [set() for _ in range(k)]
        self._witness_of: list[dict[int, int]] = [{} for _ in range(k)]  # watcher → {segment: witness}
        self._followed: dict[int, set[tuple[int, int]]] = {}  # witness → {(watcher, segment)}
        self._within: list[tuple[int, int, int, int] | None] = [None] * k  # global box, see Watch.within
        # Occupied boxes (global bounds) and how many robots stand in each. A move is one lattice step, so
        # it can only enter or leave a box one of whose edges it crosses: the boxes are also filed by
        # their finite edges (x0, x1, y0, y1: one dictionary each).
        self._occupied: dict[int, tuple[list[tuple[int, int, int, int]], list[int]]] = {}
        self._edges: tuple[dict[int, set[tuple[int, int]]], ...] = ({}, {}, {}, {})
        self._mask = np.zeros(k, dtype=np.int64)  # watched lights
        self._watchers_of_light = [0] * len(light_names)
        self._watched = 0  # the lights any watch has (a bit each)
        self._seen_at: list[frozenset[Point]] = [frozenset()] * k  # global points; see Watch.seen_at
        self.count = 0  # robots with a watch
        # Robots with a box or a long segment, and those regions as Python tuples (global frame): a few
        # are tested one by one, many in one numpy pass over the arrays above.
        self._boxed: dict[int, tuple[list[tuple[int, int, int, int]], list[tuple[int, int, int]]]] = {}
        self._with_long = 0  # robots with a long segment

    # ------------------------------------------------------------------ registering
    def register(self, r: int, watch: Watch) -> bool:
        """Watch robot r (idle, at its current position) until an event touches ``watch``; False if the
        watch has more regions than the slots (the caller keeps observing r fully)."""
        x, y = (int(v) for v in self._P[r])
        s = self._flip[r]
        segments = watch.segments
        short = [(i, dx, dy, g) for i, (dx, dy) in enumerate(watch.any_of) if (g := gcd(dx, dy)) <= SHORT]
        if watch.any_of and not short:  # every one long: the first must stay, as a plain segment
            segments = (*segments, watch.any_of[0])
        if len(watch.boxes) > BOXES or len(segments) > SEGMENTS or len(watch.occupied) > OCCUPIED:
            return False
        if watch.occupied:
            occupied = [_global_box(x, y, s, box) for box in watch.occupied]
            counts = [self._robots_in(box, r) for box in occupied]
            if not any(counts):
                return False  # the watch is broken already
        if short:
            self._intact[r] = {i for i, *_ in short}
            witnesses = self._witness_of[r]
            robot_at, followed = self._robot_at, self._followed
            for i, dx, dy, g in short:
                at = (x + dx, y + s * dy)
                # Most witnesses are chosen to be a single point away (their segment is that point).
                self._link(r, i, [at] if g == 1 else _lattice_points(x, y, dx, s * dy))
                j = robot_at.get(at)
                if j is not None:
                    witnesses[i] = j
                    followed.setdefault(j, set()).add((r, i))
            if watch.within is not None:
                self._within[r] = _global_box(x, y, s, watch.within)
        boxes = [_global_box(x, y, s, box) for box in watch.boxes]
        longs: list[tuple[int, int, int]] = []
        for i, box in enumerate(boxes):
            self._bx0[r, i], self._bx1[r, i], self._by0[r, i], self._by1[r, i] = box
        if watch.occupied:
            for i, (x0, x1, y0, y1) in enumerate(occupied):
                for edges, edge in zip(self._edges, (x0, x1, y0, y1), strict=True):
                    if abs(edge) != _BIG:
                        edges.setdefault(edge, set()).add((r, i))
            self._occupied[r] = (occupied, counts)
        for i, (dx, dy) in enumerate(segments):
            dy *= s
            g = gcd(dx, dy)
            if g <= SHORT:
                points = self._points_of[r]
                for p in _lattice_points(x, y, dx, dy):
                    points.append(p)
                    self._watchers_at.setdefault(p, set()).add(r)
            else:
                self._sdx[r, i], self._sdy[r, i], self._sg[r, i] = dx // g, dy // g, g
                longs.append((dx // g, dy // g, g))
        mask = 0
        for light in watch.lights:
            mask |= self._bit.get(light, 0)
        self._mask[r] = mask
        self._count_watchers(mask, 1)
        if watch.seen_at:
            self._seen_at[r] = frozenset((x + dx, y + s * dy) for dx, dy in watch.seen_at)
        self.active[r] = True
        self.count += 1
        if boxes or longs:
            self._boxed[r] = (boxes, longs)
            self._with_long += bool(longs)
        return True

    def _count_watchers(self, mask: int, change: int) -> None:
        """Keep ``_watched``, the lights some watch has, from a count of watchers per light."""
        counts = self._watchers_of_light
        while mask:
            bit = mask & -mask  # the lowest light of the mask
            i = bit.bit_length() - 1
            counts[i] += change
            if counts[i]:
                self._watched |= bit
            else:
                self._watched &= ~bit
            mask ^= bit

    def _robots_in(self, box: tuple[int, int, int, int], r: int) -> int:
        """How many robots other than r stand in this box (global bounds)."""
        P = self._P
        x0, x1, y0, y1 = box
        # Only the finite bounds are compared: a watch's boxes are mostly rows, strips and half-planes.
        axes = [(P[:, 0], x0, x1), (P[:, 1], y0, y1)]
        inside = None
        for column, lo, hi in axes:
            if lo == hi:
                part = column == lo
            elif lo != -_BIG and hi != _BIG:
                part = (lo <= column) & (column <= hi)
            elif lo != -_BIG:
                part = column >= lo
            elif hi != _BIG:
                part = column <= hi
            else:
                continue
            inside = part if inside is None else inside & part
        if inside is None:  # the whole plane
            return P.shape[0] - 1
        return int(np.count_nonzero(inside)) - bool(inside[r])

    def clear(self, r: int) -> None:
        """Robot r is asked again (it acted, or an event touched its watch)."""
        if not self.active[r]:
            return
        self.active[r] = False
        self.count -= 1
        self._count_watchers(int(self._mask[r]), -1)
        self._mask[r] = 0
        self._seen_at[r] = frozenset()
        points = self._points_of[r]
        if points:
            at = self._watchers_at
            for p in points:
                watchers = at[p]
                watchers.discard(r)
                if not watchers:
                    del at[p]
            self._points_of[r] = []
        if self._intact[r] or self._any_points[r] or self._witness_of[r]:
            self._unlink(r)
            self._intact[r] = set()
            followed = self._followed
            for i, j in self._witness_of[r].items():
                slots = followed[j]
                slots.discard((r, i))
                if not slots:
                    del followed[j]
            self._witness_of[r] = {}
            self._within[r] = None
        occupied = self._occupied.pop(r, None)
        if occupied is not None:
            for i, box in enumerate(occupied[0]):
                for edges, edge in zip(self._edges, box, strict=True):
                    if abs(edge) != _BIG:
                        slots = edges[edge]
                        slots.discard((r, i))
                        if not slots:
                            del edges[edge]
        boxed = self._boxed.pop(r, None)
        if boxed is not None:
            self._bx0[r] = _BIG
            self._bx1[r] = -_BIG
            self._by0[r] = _BIG
            self._by1[r] = -_BIG
            self._sg[r] = 0
            self._with_long -= bool(boxed[1])

    # ------------------------------------------------------------------ events
    def moved(
        self, old: Sequence[Point], new: Sequence[Point], movers: Sequence[int], robot_at: Mapping[Point, int]
    ) -> list[int]:
        """Watched robots these simultaneous moves concern (positions and ``robot_at``, who stands where,
        already hold the new points)."""
        self._robot_at = robot_at
        x0, y0, x1, y1 = self._reach
        for x, y in new:
            x0, y0, x1, y1 = min(x0, x), min(y0, y), max(x1, x), max(y1, y)
        self._reach = (x0, y0, x1, y1)
        if not self.count:
            return []
        # A moving witness takes its segment along: the old one is not watched, the new one is if the
        # witness is still in sight (after every point the moves touch has been marked).
        following = [
            (m, p, self._followed[m]) for m, p in zip(movers, new, strict=True) if m in self._followed
        ]
        for _, _, slots in following:
            for r, i in slots:
                self._unlink(r, i)
        hit = self._touching(list(old) + list(new))
        for m, p, slots in following:
            self._follow(m, p, slots, robot_at, hit)
        if self._occupied:
            self._recount(old, new, hit)
        if self._watched:
            for m, p in zip(movers, new, strict=True):
                self._in_sight(m, p, hit)  # it may come into sight where it now stands
            vacated = [p for p in old if p not in robot_at]  # a point another mover entered hides as before
            if vacated:
                shown = (self.bits & self._watched).nonzero()[0]
                for p in vacated:
                    if shown.size <= FEW_SHOWN:
                        for q in shown.tolist():
                            self._revealed_from(q, p, robot_at, hit)
                    else:
                        self._revealed_through(p, hit)
        return self._take(hit)

    def quiet_steps(self, r: int, start: Point, delta: Point, n: int) -> int:
        """How many of robot r's next moves, from ``start`` by ``delta`` (one lattice step along an axis),
        concern no watcher, up to n. A lower bound (0 when unsure): moving r straight to
        ``start + n′·delta`` at once then concerns nobody, as none of the n′ single moves would
        (:mod:`apf_viz.core.fast_forward`)."""
        if not self.count:
            return n
        if int(self.bits[r]) & self._watched:
            return 0  # a watched light is news wherever it comes into sight
        path = _Path(start, delta)
        mine = self._followed.get(r, set())  # segments that follow the walker: taken along, not touched
        any_at = self._any_at
        first = min(
            path.first_of(self._watchers_at, n + 1),
            path.first_of((p for p in path.on_line(any_at) if not any_at[p] <= mine), n + 1),
        )  # the first point of the walk (0 … n) that some watched region contains
        for w, (boxes, longs) in self._boxed.items():
            for box in boxes:
                first = min(first, path.first_in(path.box(box), n))
            wx, wy = int(self._P[w, 0]), int(self._P[w, 1])
            for ux, uy, g in longs:
                first = min(first, path.first_in(path.segment(wx, wy, ux, uy, g), n))
        quiet = first - 1  # the move onto that point, or off it (the start), touches it
        if mine:
            quiet = min(quiet, self._quiet_witness(r, mine, path, quiet))
        if self._occupied:
            quiet = min(quiet, self._quiet_occupied(path, n))
        if self._watched:
            quiet = min(quiet, self._quiet_reveals(r, path, n))
        return max(0, quiet)

    def _quiet_witness(self, r: int, mine: set[tuple[int, int]], path: _Path, n: int) -> int:
        """Moves during which every watcher following the walker keeps a witness in sight: another
        witness (whose segment the walk does not touch, see :meth:`quiet_steps`), or the walker itself,
        in sight and inside the watch's ``within``. (Within those moves the engine may drop and re-pick
        the walker's segment; the watcher's answer stays "same light, stay" either way.)"""
        quiet = n
        P = self._P
        touched: dict[int, set[int]] = {}  # watcher → its witnesses the walk touches
        for w, i in mine:
            touched.setdefault(w, set()).add(i)
        for w, used in touched.items():
            if self._intact[w] - used:
                continue
            within = self._within[w]
            if within is not None:
                lo, hi = path.box(within)
                if not lo <= 1 <= hi:
                    return 0
                quiet = min(quiet, hi)
            quiet = min(quiet, path.first_hidden(P, w, r, quiet + 1) - 1)
        return max(quiet, 0)

    def _quiet_occupied(self, path: _Path, n: int) -> int:
        """Moves before the walker is the last robot to leave some watch's occupied boxes."""
        quiet = n
        x, y = path.x, path.y  # where the walker stands
        for boxes, counts in self._occupied.values():
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

    def _quiet_reveals(self, r: int, path: _Path, n: int) -> int:
        """Moves before the walker leaves a point between a robot of a watched light and a watcher of
        that light (it may be revealed to the watcher then)."""
        quiet = n
        P = self._P
        for q in (self.bits & self._watched).nonzero()[0].tolist():
            watchers = self.active & ((self._mask & self.bits[q]) != 0)
            watchers[q] = False
            if watchers.any():
                quiet = min(quiet, path.first_between(P[q], P[watchers], n - 1))
        return quiet

    def relit(self, m: int, light: str) -> list[int]:
        """Watched robots robot m's new light concerns."""
        self.bits[m] = self._bit.get(light, 0)
        if not self.count:
            return []
        at = (int(self._P[m, 0]), int(self._P[m, 1]))
        hit = self._touching([at])
        self._in_sight(m, at, hit)
        return self._take(hit)

    def _in_sight(self, m: int, at: Point, hit: np.ndarray) -> None:
        """Mark the watchers of robot m's light that see m, at ``at``, unless they saw one there before.
        (Who sees m is computed only when someone watches its light.)"""
        bit = int(self.bits[m])
        if not bit & self._watched:
            return
        seen_by = visible_from(self._P, m)
        for r in seen_by[(self._mask[seen_by] & bit) != 0].tolist():
            if at not in self._seen_at[r]:
                hit[r] = True

    def _follow(
        self, m: int, p: Point, slots: set[tuple[int, int]], robot_at: Container[Point], hit: np.ndarray
    ) -> None:
        """Witness m moved to p: each watcher it still suffices for (in sight, inside the watch's
        ``within``) watches the segment to p; for the others it is touched."""
        P = self._P
        for r, i in list(slots):
            intact = self._intact[r]
            if i not in intact:
                continue
            x, y = int(P[r, 0]), int(P[r, 1])
            points = _lattice_points(x, y, p[0] - x, p[1] - y)
            within = self._within[r]
            if len(points) <= SHORT and not any(q in robot_at for q in points[:-1]) and _inside(p, within):
                self._link(r, i, points)
                continue
            slots.discard((r, i))
            del self._witness_of[r][i]
            intact.discard(i)
            if not intact:
                hit[r] = True
        if not slots:
            del self._followed[m]

    def _link(self, r: int, i: int, points: list[Point]) -> None:
        """Robot r's any-of segment i runs over these points."""
        mine = self._any_points[r]
        at = self._any_at
        for p in points:
            mine.append((p, i))
            at.setdefault(p, set()).add((r, i))

    def _unlink(self, r: int, i: int | None = None) -> None:
        """Forget the points of robot r's any-of segment i (every segment if None)."""
        at = self._any_at
        keep = []
        for p, j in self._any_points[r]:
            if i is not None and j != i:
                keep.append((p, j))
                continue
            pairs = at[p]
            pairs.discard((r, j))
            if not pairs:
                del at[p]
        self._any_points[r] = keep

    def _recount(self, old: Sequence[Point], new: Sequence[Point], hit: np.ndarray) -> None:
        """Update the robots counted in occupied boxes, and mark the watches whose boxes are all empty
        (after every move of the step: a robot may leave a box as another enters it)."""
        x0s, x1s, y0s, y1s = self._edges
        emptied = set()
        for (ox, oy), (nx, ny) in zip(old, new, strict=True):
            if oy == ny and abs(nx - ox) == 1:  # the boxes with a vertical edge between the two points
                near = x1s.get(min(ox, nx), set()) | x0s.get(max(ox, nx), set())
            elif ox == nx and abs(ny - oy) == 1:
                near = y1s.get(min(oy, ny), set()) | y0s.get(max(oy, ny), set())
            else:  # not one lattice step (the engine never moves a robot so): every box
                near = {(r, i) for r, (boxes, _) in self._occupied.items() for i in range(len(boxes))}
            for r, i in near:
                boxes, counts = self._occupied[r]
                x0, x1, y0, y1 = boxes[i]
                change = (x0 <= nx <= x1 and y0 <= ny <= y1) - (x0 <= ox <= x1 and y0 <= oy <= y1)
                if change:
                    counts[i] += change
                    emptied.add(r)
        for r in emptied:
            if not any(self._occupied[r][1]):
                hit[r] = True

    def _take(self, hit: np.ndarray) -> list[int]:
        hit &= self.active
        robots = hit.nonzero()[0].tolist()
        for r in robots:
            self.clear(r)
        return robots

    def _touching(self, points: Sequence[Point]) -> np.ndarray:
        """Robots with a box or a segment containing one of these points."""
        P = self._P
        hit = np.zeros(P.shape[0], dtype=bool)
        at = self._watchers_at
        for p in points:
            watchers = at.get(p)
            if watchers:
                hit[list(watchers)] = True
        if self._any_at:
            for p in points:
                for r, i in self._any_at.get(p, ()):
                    intact = self._intact[r]
                    intact.discard(i)
                    if not intact:
                        hit[r] = True
        if not self._boxed:
            return hit
        if len(self._boxed) <= FEW_REGIONS:
            for r, (boxes, longs) in self._boxed.items():
                if _touches(P, r, boxes, longs, points):
                    hit[r] = True
            return hit
        xs = np.array([p[0] for p in points], dtype=np.int64)
        ys = np.array([p[1] for p in points], dtype=np.int64)
        inside = (
            (self._bx0[..., None] <= xs)
            & (xs <= self._bx1[..., None])
            & (self._by0[..., None] <= ys)
            & (ys <= self._by1[..., None])
        )
        hit |= inside.any(axis=(1, 2))
        if not self._with_long:
            return hit
        for px, py in points:
            dx = px - P[:, 0]
            dy = py - P[:, 1]
            g = np.gcd(dx, dy)
            g[g == 0] = 1  # the robot standing on the point: it is not watching (it is the mover)
            qx, qy = (dx // g)[:, None], (dy // g)[:, None]
            on = (qx == self._sdx) & (qy == self._sdy) & (g[:, None] <= self._sg)
            hit |= on.any(axis=1)
        return hit

    def _revealed_from(self, q: int, p: Point, robot_at: Mapping[Point, int], hit: np.ndarray) -> None:
        """:meth:`_revealed_through` for one robot q of a watched light: if q saw the vacated point p (no
        robot between), the nearest robot beyond p on the line from q sees q now. Short ways are walked
        point by point (a crowd hides p, or stands right behind it); a long one is one numpy pass."""
        P = self._P
        qx, qy = int(P[q, 0]), int(P[q, 1])
        dx, dy = p[0] - qx, p[1] - qy
        g = gcd(dx, dy)
        ux, uy = dx // g, dy // g
        r, walked = -1, False
        if g <= WALK:
            if any((qx + t * ux, qy + t * uy) in robot_at for t in range(1, g)):
                return  # q did not see p
            x0, y0, x1, y1 = self._reach
            x, y = p
            for _ in range(WALK):
                x += ux
                y += uy
                if not (x0 <= x <= x1 and y0 <= y <= y1):
                    walked = True  # out of every robot's reach: nobody beyond p
                    break
                r = robot_at.get((x, y), -1)
                if r != -1:
                    walked = True
                    break
        if not walked:
            r, d = _nearest_along(P, q, ux, uy)
            if d < g:
                return  # q did not see p
        if r != -1 and self._mask[r] & self.bits[q] and (qx, qy) not in self._seen_at[r]:
            hit[r] = True

    def _revealed_through(self, p: Point, hit: np.ndarray) -> None:
        """Mark the watchers to which a robot with a watched light is revealed now that p is empty
        (unless they saw one at that point before): along each line through p, the nearest robots on
        the two sides see each other now."""
        P = self._P
        dx = P[:, 0] - p[0]
        dy = P[:, 1] - p[1]
        span = int(max(np.abs(dx).max(), np.abs(dy).max())) + 1
        if span >= PACKED_SPAN_LIMIT:
            hit |= (self._mask & np.bitwise_or.reduce(self.bits)) != 0  # exact by excess
            return
        g = np.gcd(dx, dy)
        key = (dx // g) * (2 * span + 1) + dy // g  # one per primitive direction; −key is the opposite
        order = np.lexsort((g, key))
        skey = key[order]
        first = np.empty(skey.size, dtype=bool)
        first[0] = True
        np.not_equal(skey[1:], skey[:-1], out=first[1:])
        nearest, nkey = order[first], skey[first]  # the nearest robot in each direction, keys ascending
        j = np.searchsorted(nkey, -nkey)
        j[j >= nkey.size] = 0
        paired = nkey[j] == -nkey
        a, b = nearest[paired], nearest[j[paired]]  # a and b face each other across p
        news = (self._mask[a] & self.bits[b]) != 0
        points = self._P
        for r, q in zip(a[news].tolist(), b[news].tolist(), strict=True):
            if (int(points[q, 0]), int(points[q, 1])) not in self._seen_at[r]:
                hit[r] = True


def _nearest_along(P: np.ndarray, q: int, ux: int, uy: int) -> tuple[int, int]:
    """The robot nearest to robot q along the primitive direction (ux, uy), and its distance in lattice
    steps; (−1, 0) if there is none. Products of a direction and a gcd only: nothing can overflow."""
    ox = P[:, 0] - P[q, 0]
    oy = P[:, 1] - P[q, 1]
    g = np.gcd(ox, oy)
    on = ((ox == ux * g) & (oy == uy * g) & (g > 0)).nonzero()[0]
    if not on.size:
        return -1, 0
    i = int(on[np.argmin(g[on])])
    return i, int(g[i])


def _touches(
    P: np.ndarray,
    r: int,
    boxes: list[tuple[int, int, int, int]],
    longs: list[tuple[int, int, int]],
    points: Sequence[Point],
) -> bool:
    """Whether one of these points lies in one of robot r's boxes or long segments (global frame)."""
    for px, py in points:
        for x0, x1, y0, y1 in boxes:
            if x0 <= px <= x1 and y0 <= py <= y1:
                return True
        if longs:
            dx, dy = px - int(P[r, 0]), py - int(P[r, 1])
            g = gcd(dx, dy)
            if g and any(dx == ux * g and dy == uy * g and g <= length for ux, uy, length in longs):
                return True
    return False


class _Path:
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
        if span >= _VECTOR_SPAN:
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


def _inside(p: Point, box: tuple[int, int, int, int] | None) -> bool:
    return box is None or (box[0] <= p[0] <= box[1] and box[2] <= p[1] <= box[3])


def _global_box(x: int, y: int, s: int, box: Box) -> tuple[int, int, int, int]:
    """A box of the robot at (x, y) whose local +y is the global s·y, as global bounds (±2^62 for None)."""
    x0, x1, y0, y1 = box
    if s == -1:  # the robot's +y is the global −y: its box flips about its own row
        y0, y1 = (None if y1 is None else -y1), (None if y0 is None else -y0)
    return (
        -_BIG if x0 is None else x + x0,
        _BIG if x1 is None else x + x1,
        -_BIG if y0 is None else y + y0,
        _BIG if y1 is None else y + y1,
    )
