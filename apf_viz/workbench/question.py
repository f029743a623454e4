"""A lecture stop's question answered by the run: from where the stop left it, the run goes on under the
lecture's scheduler and seed until it shows the answer (a robot moves, a robot's light changes, the run
ends), and comes back. The answer is what the run does, never what an author wrote, so a lecture whose
run changes (another algorithm, another start) changes its answers with it, and ``lecture check`` prints
them. Pure: no viser.

What counts (docs/LECTURES.md):

- ``robot``, "which robot moves next": the robots whose cell changes in the first step that moves any
  (several under FSYNC, each right). A Look or a Compute changes nothing the room sees, so "acts" is
  read as "moves".
- ``cell``, "where does robot r move next": the cell robot r stands on after its first step that moves
  it, on the grid (x to the right, y up, as the canvas and the event line give it).
- ``light``, "which light does robot r turn on next": robot r's light after its first step that
  changes it.
- ``outcome``: the run's outcome (formed, collision, stuck); a run still going at the cap has none.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np

from apf_viz.core.engine import Engine
from apf_viz.lecture import Question

ANSWER_WITHIN = 200_000
"""Events the run may take from a stop to answer its question; past them it cannot, and the stop fails."""


class Runs(Protocol):
    """What a question is answered on: a run that steps and seeks (a session: workbench/lecturer.py)."""

    @property
    def engine(self) -> Engine:
        """The run's engine, where the run stands now."""
        ...

    def step(self) -> bool:
        """One step chosen by the scheduler; False if nothing ran."""
        ...

    def seek(self, step: float) -> None:
        """Go to that step of the history (how the run is put back)."""
        ...


@dataclass(frozen=True)
class Answer:
    """A question's answer, as the run gave it: the right choices (each as :func:`choice_words` reads
    it), and the step and event at which the run shows it."""

    question: Question
    right: frozenset[str]
    step: int
    event: int

    def words(self) -> str:
        """The right choices in words, joined by "or" (robots and cells in order)."""
        return " or ".join(choice_words(self.question.kind, c) for c in sorted(self.right, key=_order))


def _order(choice: str) -> tuple[int | str, ...]:
    parts = choice.split(",")
    return (0, *map(int, parts)) if all(p.lstrip("-").isdigit() for p in parts) else (1, choice)


def choice_words(kind: str, choice: str) -> str:
    """A choice as the screen says it: ``robot 3``, ``(2, −1) on the grid``, ``leader1``, ``formed``."""
    if kind == "robot":
        return f"robot {choice}"
    if kind == "cell":
        x, y = choice.split(",")
        return f"({x}, {y}) on the grid".replace("-", "−")
    return choice


def cell_choice(x: int, y: int) -> str:
    """A cell as a choice is spelled: ``x,y``."""
    return f"{x},{y}"


def answer(run: Runs, question: Question, within: int = ANSWER_WITHIN) -> Answer | str:
    """What the run does from where it stands, for ``question``; or, in words, why it cannot say (no
    robot acts, the run ends first, the cap comes first). The run is put back where it stood."""
    engine = run.engine
    start = engine.step_index
    k = len(engine.positions)
    if question.robot is not None and question.robot >= k:
        return f"asks about robot {question.robot}, but the run has {k} robots (0–{k - 1})"
    try:
        return _run_to_answer(run, question, within)
    finally:
        run.seek(start)


def _run_to_answer(run: Runs, question: Question, within: int) -> Answer | str:
    engine = run.engine
    positions = engine.positions.copy()
    lights = list(engine.state.lights)
    cap = engine.state.events + within
    r = question.robot
    while True:
        if question.kind == "outcome" and engine.outcome is not None:
            if engine.outcome == "limit":
                return "the run reached its event limit: it shows no outcome to ask about"
            return _answered(question, {engine.outcome}, engine)
        if engine.state.events >= cap:
            return f"the run shows no answer within {within:,} events of the stop"
        before = engine.step_index
        if engine.finished or not run.step() or engine.step_index == before:  # (Compare's run beside it)
            said = (
                f"ended ({engine.outcome})"
                if engine.outcome
                else "goes no further (nobody acts, or a trace ends)"
            )
            return f"the run {said} before it answers"
        now = _tried(engine)
        if question.kind == "robot":
            moved = np.flatnonzero((now != positions).any(axis=1))
            if len(moved):
                return _answered(question, {str(int(i)) for i in moved}, engine)
        elif question.kind == "cell" and r is not None and tuple(now[r]) != tuple(positions[r]):
            return _answered(question, {cell_choice(int(now[r][0]), int(now[r][1]))}, engine)
        elif question.kind == "light" and r is not None and engine.state.lights[r] != lights[r]:
            return _answered(question, {engine.state.lights[r]}, engine)


def _tried(engine: Engine) -> np.ndarray:
    """Where the robots stand, or, after a collision, where they went: the colliding move is the room's
    answer to where a robot moves next, though the engine does not apply it."""
    now = engine.positions
    if engine.outcome != "collision":
        return now
    now = now.copy()
    for ev in engine.history.steps[engine.step_index - 1].events:
        if ev.phase == "move" and ev.collision and ev.to is not None:
            now[ev.robot] = ev.to
    return now


def _answered(question: Question, right: set[str], engine: Engine) -> Answer:
    return Answer(question, frozenset(right), engine.step_index, engine.state.events)
