"""What the library's functions start from: a start and a pattern given as a shipped name, a file, or
the points themselves, read and checked exactly as the command line reads them."""

from __future__ import annotations

import json
import numbers
import os
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

from apf_viz.core.formats import (
    InputError,
    PatternFile,
    RobotsFile,
    check_sizes,
    load_pattern,
    load_robots,
    parse_pattern,
    parse_robots,
)
from apf_viz.core.grid import Point, as_point
from apf_viz.demos import shipped_file

Points = str | os.PathLike[str] | Sequence[Sequence[int]]
"""A shipped name (``"sym-call-7"``), a path to a JSON file, or the points themselves."""


@dataclass(frozen=True)
class Start:
    """A start and its pattern, read and checked: the robots' points and, if the file gives them, their
    y-axes; the pattern's points; the names the inputs were given by (for messages and titles)."""

    robots: list[Point]
    y_up: list[bool] | None
    pattern: list[Point]
    robots_name: str
    pattern_name: str

    def flips(self, seed: int) -> list[bool]:
        """The robots' y-axes: the file's, or the adversary's random choice from ``seed`` (as ``run``)."""
        return RobotsFile(robots=self.robots, y_up=self.y_up).flips(seed)


def start_of(robots: Points, pattern: Points) -> Start:
    """Read ``robots`` and ``pattern`` (an :class:`InputError` in one line names a bad one)."""
    r, r_name = _read(robots, "robots")
    p, p_name = _read(pattern, "pattern")
    assert isinstance(r, RobotsFile) and isinstance(p, PatternFile)
    check_sizes(r, p, p_name)
    return Start(
        [as_point(q) for q in r.robots],
        None if r.y_up is None else list(r.y_up),
        [as_point(q) for q in p.points],
        r_name,
        p_name,
    )


def _read(given: Points, kind: str) -> tuple[RobotsFile | PatternFile, str]:
    if isinstance(given, str | os.PathLike):
        path = Path(given)
        if not path.exists():
            found = shipped_file(str(given), kind)
            if found is None:
                raise InputError(f"{kind} {str(given)!r}: no such file, and no shipped {kind} of that name")
            path = found
        return (load_robots(path) if kind == "robots" else load_pattern(path)), path.name
    if isinstance(given, bytes | bytearray) or not isinstance(given, Sequence | Iterable):
        raise InputError(f"{kind} {given!r}: a shipped name, a JSON file's path, or the points [(x, y), …]")
    points = [_point(point, kind) for point in given]
    # As a file would say them: numpy's integers as integers, anything else left for the check to refuse.
    text = json.dumps({"robots": points} if kind == "robots" else {"points": points}, default=_plain)
    where = f"the {kind} given"
    return (parse_robots(text, where) if kind == "robots" else parse_pattern(text, where)), where


def _point(point: object, kind: str) -> list[object]:
    if isinstance(point, str | bytes) or not isinstance(point, Sequence | Iterable):
        raise InputError(f"{kind}: {point!r} is not a point (x, y)")
    return list(point)


def _plain(value: object) -> object:
    if isinstance(value, numbers.Integral):
        return int(value)
    raise InputError(f"{value!r} is not a grid coordinate (an integer)")


def whole_number(
    name: str, value: object, low: int = 1, high: int | None = None, says: str | None = None
) -> int:
    """An integer argument (never a bool, a float or a string) from ``low`` to ``high``, or the one-line
    :class:`InputError` naming it (and saying ``says``, or the range)."""
    ok = isinstance(value, int) and not isinstance(value, bool) and value >= low
    if not ok or (high is not None and value > high):  # type: ignore[operator]
        span = f"{low:,} or more" if high is None else f"{low:,} to {high:,}"
        raise InputError(f"{name} {value!r}: {says or 'a whole number, ' + span}")
    return value  # type: ignore[return-value]


def whole_numbers(name: str, values: object, low: int = 1) -> list[int]:
    """A list of integer arguments (``ks=[4, 6]``, ``seeds=range(3)``), or the one-line InputError."""
    if isinstance(values, str | bytes) or not isinstance(values, Iterable):
        raise InputError(f"{name} {values!r}: a list of whole numbers, such as [4, 6] or range(1, 4)")
    given = list(values)
    for v in given:
        if isinstance(v, bool) or not isinstance(v, int) or v < low:
            raise InputError(f"{name} {given!r}: {name} are whole numbers, {low} or more (not {v!r})")
    return given
