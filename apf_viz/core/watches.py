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

from collections.abc import Container, Mapping, Sequence
from math import gcd

import numpy as np

from apf_viz.core.algorithm import Box, Watch
from apf_viz.core.grid import PACKED_SPAN_LIMIT, Point, visible_from
from apf_viz.core.watch_geometry import (
    BIG,
    global_box,
    inside,
    lattice_points,
    nearest_along,
    robots_in,
    touches,
)

BOXES = 2  # per robot; a watch with more regions is not registered (the robot stays fully observed)
SEGMENTS = 2
OCCUPIED = 2
FEW_REGIONS = 16  # up to this many robots with boxes or long segments, they are tested one by one
WALK = 32  # lattice points walked, looking for a robot, before one numpy pass over every robot
FEW_SHOWN = 8  # up to this many robots of watched lights, a reveal is looked for from each of them
SHORT = 64  # a segment of at most this many lattice steps is kept as its points


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
        self._bx0 = np.full((k, BOXES), BIG, dtype=np.int64)
        self._bx1 = np.full((k, BOXES), -BIG, dtype=np.int64)
        self._by0 = np.full((k, BOXES), BIG, dtype=np.int64)
        self._by1 = np.full((k, BOXES), -BIG, dtype=np.int64)
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
            occupied = [global_box(x, y, s, box) for box in watch.occupied]
            counts = [robots_in(self._P, box, r) for box in occupied]
            if not any(counts):
                return False  # the watch is broken already
        if short:
            self._register_witnesses(r, short, watch.within)
        boxes = [global_box(x, y, s, box) for box in watch.boxes]
        for i, box in enumerate(boxes):
            self._bx0[r, i], self._bx1[r, i], self._by0[r, i], self._by1[r, i] = box
        if watch.occupied:
            for i, (x0, x1, y0, y1) in enumerate(occupied):
                for edges, edge in zip(self._edges, (x0, x1, y0, y1), strict=True):
                    if abs(edge) != BIG:
                        edges.setdefault(edge, set()).add((r, i))
            self._occupied[r] = (occupied, counts)
        longs = self._register_segments(r, segments)
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

    def _register_witnesses(self, r: int, short: list[tuple[int, int, int, int]], within: Box | None) -> None:
        """Robot r's ``any_of`` witnesses (``short``: index, offset in r's frame, lattice length): each
        segment linked to r, and the robot standing at its end followed (its moves touch the watch)."""
        x, y = (int(v) for v in self._P[r])
        s = self._flip[r]
        self._intact[r] = {i for i, *_ in short}
        witnesses = self._witness_of[r]
        robot_at, followed = self._robot_at, self._followed
        for i, dx, dy, g in short:
            at = (x + dx, y + s * dy)
            # Most witnesses are chosen to be a single point away (their segment is that point).
            self._link(r, i, [at] if g == 1 else lattice_points(x, y, dx, s * dy))
            j = robot_at.get(at)
            if j is not None:
                witnesses[i] = j
                followed.setdefault(j, set()).add((r, i))
        if within is not None:
            self._within[r] = global_box(x, y, s, within)

    def _register_segments(self, r: int, segments: Sequence[Point]) -> list[tuple[int, int, int]]:
        """Robot r's watched segments (offsets in its frame): a short one as its points, a long one by
        its direction and length (returned, as (ux, uy, length))."""
        x, y = (int(v) for v in self._P[r])
        s = self._flip[r]
        longs: list[tuple[int, int, int]] = []
        for i, (dx, dy) in enumerate(segments):
            dy *= s
            g = gcd(dx, dy)
            if g <= SHORT:
                points = self._points_of[r]
                for p in lattice_points(x, y, dx, dy):
                    points.append(p)
                    self._watchers_at.setdefault(p, set()).add(r)
            else:
                self._sdx[r, i], self._sdy[r, i], self._sg[r, i] = dx // g, dy // g, g
                longs.append((dx // g, dy // g, g))
        return longs

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
                    if abs(edge) != BIG:
                        slots = edges[edge]
                        slots.discard((r, i))
                        if not slots:
                            del edges[edge]
        boxed = self._boxed.pop(r, None)
        if boxed is not None:
            self._bx0[r] = BIG
            self._bx1[r] = -BIG
            self._by0[r] = BIG
            self._by1[r] = -BIG
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
            dx, dy = p[0] - x, p[1] - y  # the length first: a far witness's segment is never listed
            if gcd(dx, dy) <= SHORT and inside(p, self._within[r]):
                points = lattice_points(x, y, dx, dy)
                if not any(q in robot_at for q in points[:-1]):
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
                if touches(P, r, boxes, longs, points):
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
            r, d = nearest_along(P, q, ux, uy)
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
