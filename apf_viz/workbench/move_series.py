"""Moves over events: the series behind the live plot, kept incrementally as the run grows.

A frame asks for the series at the current step; a long run has hundreds of thousands of steps and a
frame must not walk them. The per-step totals are extended only by newly recorded steps, and a read
samples at most ``SERIES_POINTS`` of the steps where the move count changed.
"""

from __future__ import annotations

from array import array
from bisect import bisect_right
from collections.abc import Sequence

import numpy as np

from apf_viz.core.grid import Point
from apf_viz.core.history import History

SERIES_POINTS = 600  # the live plot's resolution: more points than this cost frames and show nothing new


class MoveSeries:
    """(events so far, moves so far) after each recorded step of one run's history.

    A move counts as the engine counts it: a Move event without collision that changes the robot's
    cell. A branch rewrites the history (its ``generation`` changes), or another history is asked about,
    and the series starts over."""

    def __init__(self, start: Sequence[Point]) -> None:
        self._start = list(start)
        self._history: History | None = None
        self._generation = -1
        self._clear()

    def _clear(self) -> None:
        self._events = array("q", [0])  # per recorded step (index 0: the start)
        self._moves = array("q", [0])
        self._changes = array("q", [0])  # the steps where the move count changed, after step 0
        self._positions = list(self._start)

    def at(self, history: History, step: int, limit: int = SERIES_POINTS) -> tuple[tuple[int, int], ...]:
        """The start, every step up to ``step`` that changed the move count, and ``step`` itself,
        evenly thinned to at most ``limit`` points (the first and the latest always kept)."""
        if history is not self._history or self._generation != history.generation:
            self._history, self._generation = history, history.generation
            self._clear()
        self._extend(history, step)
        n = bisect_right(self._changes, step)
        if n <= limit - 1:
            chosen: Sequence[int] = self._changes[:n]
        else:
            picks = np.unique(np.linspace(0, n - 1, limit - 1).astype(np.int64))
            chosen = [self._changes[int(i)] for i in picks]
        points = [(self._events[s], self._moves[s]) for s in chosen]
        if chosen[-1] != step:
            points.append((self._events[step], self._moves[step]))
        return tuple(points)

    def _extend(self, history: History, step: int) -> None:
        done = len(self._events) - 1
        if step <= done:
            return
        events, moves, pos = self._events[-1], self._moves[-1], self._positions
        for effects in history.effects(done, step):
            before = moves
            for ev in effects:
                if ev.moved and ev.to is not None and ev.to != pos[ev.robot]:
                    pos[ev.robot] = ev.to
                    moves += 1
            events += len(effects)
            self._events.append(events)
            self._moves.append(moves)
            if moves != before:
                self._changes.append(len(self._events) - 1)
