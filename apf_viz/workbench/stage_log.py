"""Where each stage of the run began: the timeline's marks, kept incrementally as the run grows.

The algorithm names the stage of a configuration (core/portrayal.py, ``Overlays.stage``: "headline —
detail"). A frame asks for the marks up to the current step; like :class:`~apf_viz.workbench.move_series.
MoveSeries`, the log replays only newly recorded steps, keeping positions and lights as it goes, and asks
the algorithm for the stage only after a step that moved a robot or changed a light.
"""

from __future__ import annotations

from bisect import bisect_right
from collections.abc import Callable, Sequence

from apf_viz.core.grid import Point
from apf_viz.core.history import History

StageOf = Callable[[tuple[Point, ...], tuple[str, ...]], str]
# Above this many robots only light changes are read: naming the stage costs O(k), and a move of one
# robot in a thousand rarely changes it. A stage begun by moves alone is then marked late or not at all.
MOVES_READ_UP_TO_K = 200
# Labels on the timeline at least this share of its length apart (a label is about a fifth of the slider).
LABEL_GAP = 0.2


def headline(stage: str) -> str:
    """A stage's headline, the part before " — " (the timeline labels a mark only where it changes)."""
    return stage.split(" — ")[0]


class StageLog:
    """(step, stage) at each step where the stage changed, from the start of one run's history.

    A branch rewrites the history (its ``generation`` changes), or another history is asked about, and
    the log starts over."""

    def __init__(self, start: Sequence[Point], lights: Sequence[str], stage_of: StageOf) -> None:
        self._start, self._start_lights = list(start), list(lights)
        self._stage_of = stage_of
        self._history: History | None = None
        self._generation = -1
        self._clear()

    def _clear(self) -> None:
        self._positions = list(self._start)
        self._lights = list(self._start_lights)
        self._done = 0  # steps replayed
        first = self._stage_of(tuple(self._positions), tuple(self._lights))
        self._steps: list[int] = [0]
        self._stages: list[str] = [first]

    def changes(self, history: History, step: int) -> list[tuple[int, str]]:
        """(step, stage) where each stage began, up to ``step`` (the start's stage at step 0)."""
        if history is not self._history or self._generation != history.generation:
            if self._history is not None:  # a new history (a branch): the start's stage is kept
                self._clear()
            self._history, self._generation = history, history.generation
        self._extend(history, step)
        n = bisect_right(self._steps, step)
        return list(zip(self._steps[:n], self._stages[:n], strict=True))

    def marks(self, history: History, step: int) -> tuple[tuple[int, str | None], ...]:
        """The timeline's marks: every stage change after the start, labelled where the headline
        changes ("Phase 2", "Formed": its text before a colon), unlabelled within one headline."""
        out: list[tuple[int, str | None]] = []
        previous, labelled = "", None  # the index in ``out`` of the last labelled mark
        for at, stage in self.changes(history, step):
            head = headline(stage)
            if at > 0 and head != previous:
                if labelled is not None and at - out[labelled][0] < LABEL_GAP * step:
                    # Labels this close print over each other: the later phase keeps its label (it
                    # names what follows), the earlier mark stays, unlabelled.
                    out[labelled] = (out[labelled][0], None)
                labelled = len(out)
                out.append((at, head.split(":")[0]))
            elif at > 0:
                out.append((at, None))
            previous = head
        return tuple(out)

    def _extend(self, history: History, step: int) -> None:
        if step <= self._done:
            return
        pos, lights = self._positions, self._lights
        read_moves = len(pos) <= MOVES_READ_UP_TO_K
        for i, effects in enumerate(history.effects(self._done, step), start=self._done + 1):
            changed = False
            for ev in effects:
                if ev.light is not None and ev.light != lights[ev.robot]:
                    lights[ev.robot] = ev.light
                    changed = True
                elif ev.moved and ev.to is not None and ev.to != pos[ev.robot]:
                    pos[ev.robot] = ev.to
                    changed |= read_moves
            if changed:
                now = self._stage_of(tuple(pos), tuple(lights))
                if now != self._stages[-1]:
                    self._steps.append(i)
                    self._stages.append(now)
        self._done = max(self._done, step)
