"""The snapshot a robot gets from a Look: the only thing an algorithm ever receives.

It holds, in the robot's own frame (itself at the origin, x agreed, y possibly flipped), the offset and the
light of every robot it can see, and its own light. Nothing else: no global coordinate, no id, no robot
count. Visible robots are sorted by offset (dx, then dy), so the order itself carries no identity, and
algorithms may rely on it (the robots of one vertical line are a contiguous run).

The same snapshot reads two ways, each made on first use from the other: ``robots``, a tuple of
:class:`Seen` (clear, for rules that look at a few robots), and ``columns``, numpy arrays of the same
robots in the same order (for rules that scan hundreds of them: a view of 800 robots costs 140 µs to
turn into tuples and a Python pass to scan, a few µs as arrays). Which one the engine made is invisible
to the algorithm: both describe the same robots.
"""

from __future__ import annotations

from bisect import bisect_left
from collections.abc import Iterator
from dataclasses import dataclass
from itertools import repeat
from typing import NamedTuple

import numpy as np

from apf_viz.core.grid import Point

_CHUNK = 16  # robots turned into tuples at a time by Snapshot.iter_between


class Seen(NamedTuple):
    """One visible robot: offset (dx, dy) in the observer's frame, and its light."""

    dx: int
    dy: int
    light: str


@dataclass(frozen=True, eq=False, slots=True)
class Columns:
    """The visible robots as arrays, in the snapshot's order: ``dx``, ``dy`` (int64) and ``code``, each
    robot's light as an index into ``palette`` (a tuple of light names); ``present``, if known, the
    codes that occur, a bit each (the compiled view build counts them on its way)."""

    dx: np.ndarray
    dy: np.ndarray
    code: np.ndarray
    palette: tuple[str, ...]
    present: int | None = None

    def showing(self, light: str) -> np.ndarray:
        """Boolean mask of the robots showing this light."""
        try:
            mask: np.ndarray = self.code == self.palette.index(light)
            return mask
        except ValueError:
            return np.zeros(self.code.shape, dtype=bool)

    def entries(self, lo: int = 0, hi: int | None = None) -> list[Seen]:
        """The robots lo..hi (every robot by default) as :class:`Seen`, in order."""
        names = [self.palette[i] for i in self.code[lo:hi].tolist()]
        # tuple.__new__ mapped in C: a NamedTuple's own __new__ is a Python function, 20× slower here.
        return list(
            map(
                tuple.__new__,
                repeat(Seen),
                zip(self.dx[lo:hi].tolist(), self.dy[lo:hi].tolist(), names, strict=True),
            )
        )

    def seen(self, i: int) -> Seen:
        """The i-th visible robot as a :class:`Seen`."""
        return Seen(int(self.dx[i]), int(self.dy[i]), self.palette[int(self.code[i])])


class Snapshot:
    """What one Look returns: the robot's own ``light`` and the robots it sees. Hashable and compared by
    content (light and robots), so identical views share one cached decision.

    Args:
        light: the observer's own light.
        robots: the visible robots, sorted by (dx, dy); or None when ``columns`` is given.
        columns: the same as arrays (:class:`Columns`); made from ``robots`` if not given.
    """

    __slots__ = ("_columns", "_robots", "light")

    def __init__(self, light: str, robots: tuple[Seen, ...] | None = None, columns: Columns | None = None):
        if robots is None and columns is None:
            robots = ()
        self.light = light
        self._robots = robots
        self._columns = columns

    @property
    def robots(self) -> tuple[Seen, ...]:
        """The visible robots, sorted by (dx, dy) (made from the arrays on first use)."""
        robots = self._robots
        if robots is None:
            assert self._columns is not None  # a snapshot holds one of the two
            robots = self._robots = tuple(self._columns.entries())
        return robots

    @property
    def columns(self) -> Columns:
        """The visible robots as arrays (made from :attr:`robots` on first use)."""
        columns = self._columns
        if columns is None:
            robots = self._robots
            assert robots is not None  # a snapshot holds one of the two
            palette = tuple(sorted({s.light for s in robots}))
            index = {name: i for i, name in enumerate(palette)}
            columns = self._columns = Columns(
                np.fromiter((s.dx for s in robots), dtype=np.int64, count=len(robots)),
                np.fromiter((s.dy for s in robots), dtype=np.int64, count=len(robots)),
                np.fromiter((index[s.light] for s in robots), dtype=np.uint8, count=len(robots)),
                palette,
            )
        return columns

    def __len__(self) -> int:
        """How many robots it sees."""
        return len(self._robots) if self._robots is not None else int(self.columns.dx.shape[0])

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Snapshot):
            return NotImplemented
        return self is other or (self.light == other.light and self.robots == other.robots)

    def __hash__(self) -> int:
        return hash((self.light, self.robots))

    def __repr__(self) -> str:
        return f"Snapshot(light={self.light!r}, robots={self.robots!r})"

    def __reduce__(self) -> tuple[type[Snapshot], tuple[str, tuple[Seen, ...]]]:
        return (Snapshot, (self.light, self.robots))

    # Ranges of the view, in its order, read off whichever form it has: a rule that needs a vertical line
    # or the left half of a large view need not turn all of it into tuples (a leader's appearance makes
    # a thousand robots decide anew, each over hundreds of robots).
    def column_start(self, dx: int, lo: int = 0) -> int:
        """The index of the first robot from ``lo`` on whose offset is at least ``dx`` horizontally (the
        view is sorted by dx: a bisection)."""
        robots = self._robots
        if robots is not None:
            return bisect_left(robots, (dx,), lo)
        return lo + int(np.searchsorted(self.columns.dx[lo:], dx))

    def dx_at(self, i: int) -> int:
        """The horizontal offset of the i-th robot."""
        robots = self._robots
        return robots[i].dx if robots is not None else int(self.columns.dx[i])

    def between(self, lo: int, hi: int) -> tuple[Seen, ...]:
        """The robots lo..hi (a slice of :attr:`robots`)."""
        robots = self._robots
        return robots[lo:hi] if robots is not None else tuple(self.columns.entries(lo, hi))

    def iter_between(self, lo: int, hi: int) -> Iterator[Seen]:
        """The robots lo..hi one by one, made as they are asked for (in chunks): for a scan that usually
        stops after a few."""
        robots = self._robots
        if robots is not None:
            yield from robots[lo:hi]
            return
        for a in range(lo, hi, _CHUNK):
            yield from self.columns.entries(a, min(a + _CHUNK, hi))

    def count(self, light: str) -> int:
        """How many of the robots it sees show this light."""
        if self._robots is not None:
            return sum(1 for s in self._robots if s.light == light)
        return int(np.count_nonzero(self.columns.showing(light)))

    def at(self, dx: int, dy: int) -> Seen | None:
        """The visible robot at this offset, if any."""
        for s in self.robots:
            if s.dx == dx and s.dy == dy:
                return s
        return None

    def offsets(self) -> list[Point]:
        """The visible robots' offsets (dx, dy), in the robot's own frame."""
        return [(s.dx, s.dy) for s in self.robots]

    def lights(self) -> set[str]:
        """The lights it sees (read off the arrays when the snapshot has them: no tuple is made)."""
        if self._robots is not None:
            return {s.light for s in self._robots}
        c = self.columns
        if c.present is not None:
            palette, bits = c.palette, c.present
            return {palette[i] for i in range(bits.bit_length()) if bits >> i & 1}
        counts = np.bincount(c.code, minlength=len(c.palette))
        return {c.palette[i] for i in counts.nonzero()[0].tolist()}
