"""Compare: the same start, pattern and adversary under a second algorithm, stepping with the run.

The twin engine applies exactly the run's step records (who acts, in which round). A robot's phase
depends only on how often it was activated, so the same records drive any algorithm; the twin stops
where its own run ends (formed, collision, stuck) and the run goes on. It is brought to the run's step
lazily, when a frame is drawn (after a step, Back, the timeline or a branch), so no control needs to
know about it.

When the run has ended and the twin has not, Step goes on with the twin alone, its steps chosen by the
same scheduler and seed as the run's (a scheduler's choice is a function of the seed and the step
number); those steps are kept while the run stays at its end, and dropped when it leaves it.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import NamedTuple

from apf_viz.algorithms import Factory, get_algorithm
from apf_viz.core.engine import Engine
from apf_viz.core.history import Event
from apf_viz.core.schedulers import BY_HAND, make_scheduler, step_rng
from apf_viz.workbench.run_config import RunConfig


class Divergence(NamedTuple):
    """The first decision at which the two runs differ: its event number, both sides in words, its robot,
    and (once it has happened in both runs, else "") the move that follows it in each: its consequence."""

    event: int
    what: str
    robot: int
    consequence: str = ""


class Twin:
    """A second engine that follows the run's steps, and the first event where the two differ."""

    def __init__(self, algorithm: str, plugins: Mapping[str, Factory] | None = None) -> None:
        get_algorithm(algorithm, plugins)  # refuses an unknown name before anything changes
        self.algorithm = algorithm
        self._plugins = plugins
        self.engine: Engine | None = None
        self._config: RunConfig | None = None
        # The run (its engine and history generation) at whose end the twin went on alone, if it did.
        self._alone_after: tuple[int, int, int] | None = None
        # (history generations, steps compared, events in them, the divergence found): scanned once.
        self._divergence: tuple[tuple[int, int], int, int, Divergence | None] = ((-1, -1), 0, 0, None)

    def follow(self, run: Engine, config: RunConfig) -> Engine:
        """The twin at the run's step (rebuilt when the run's configuration changed)."""
        if self.engine is None or config != self._config:
            self._config = config
            self.engine = config.but(algorithm=self.algorithm).engine(self._plugins)
        twin = self.engine
        target = run.step_index
        if twin.step_index > target and self._alone_after != (id(run), run.history.generation, target):
            self._alone_after = None
            twin.seek(min(target, twin.history.length))
        while twin.step_index < target and not twin.finished:
            twin.apply(run.history.steps.record(twin.step_index))
        return twin

    def goes_on_alone(self, run: Engine, config: RunConfig) -> bool:
        """Whether the twin can step on past the run's end: the run has ended, the twin has not, and a
        scheduler (not Manual) chooses its steps."""
        return run.finished and config.scheduler not in BY_HAND and not self.follow(run, config).finished

    def step_alone(self, run: Engine, config: RunConfig) -> bool:
        """One step of the twin past the run's end (the run's scheduler and seed choose it). False if
        it cannot go on alone (:meth:`goes_on_alone`)."""
        if not self.goes_on_alone(run, config):
            return False
        twin = self.follow(run, config)
        scheduler = make_scheduler(config.scheduler)
        twin.apply(scheduler.choose(twin, step_rng(config.seed, twin.step_index)))
        self._alone_after = (id(run), run.history.generation, run.step_index)
        return True

    def divergence(self, run: Engine) -> Divergence | None:
        """The first decision at which the two runs differ (a Compute whose rule, target or light
        differs; a Move differs only after one), with the move that follows it; None while they agree.
        Only a decision the run has reached is named."""
        twin = self.engine
        if twin is None:
            return None
        key = (run.history.generation, twin.history.generation)
        cached_key, checked, events, found = self._divergence
        if cached_key != key:
            checked, events, found = 0, 0, None
        upto = min(run.step_index, twin.step_index)
        while found is None and checked < upto:
            pairs = zip(run.history.steps[checked].events, twin.history.steps[checked].events, strict=False)
            for a, b in pairs:
                events += 1
                if _differs(a, b):
                    found = Divergence(events, f"{describe(a)} | {describe(b)}", a.robot)
                    break
            checked += 1
        self._divergence = (key, checked, events, found)
        if found is None or found.event > run.state.events:
            return None
        # The scan stopped after the step the divergence lies in.
        return found._replace(consequence=self._consequence(run, twin, found.robot, checked - 1))

    @staticmethod
    def _consequence(run: Engine, twin: Engine, robot: int, step: int) -> str:
        """The Move of ``robot`` after the differing Compute (in step ``step``), in each run, once both
        have made it."""
        moves = [_next_move(engine, step, robot) for engine in (run, twin)]
        if any(m is None for m in moves):
            return ""
        return " | ".join(describe(m) for m in moves if m is not None)


def _next_move(engine: Engine, after: int, robot: int) -> Event | None:
    """The first Move of ``robot`` in the steps after step ``after`` that ``engine`` has taken."""
    for i in range(after + 1, engine.step_index):
        for e in engine.history.steps[i].events:
            if e.robot == robot and e.phase == "move":
                return e
    return None


def _differs(a: Event, b: Event) -> bool:
    """A different decision: another rule fired, another target (the pending move), or another light. A
    Move differs only where a decision differed before it, or a collision stopped one run."""
    if a.phase == "compute":
        return a.rule_id != b.rule_id or a.move != b.move or a.light != b.light
    if a.phase == "move":
        return a.to != b.to or a.collision != b.collision
    return False


def describe(ev: Event) -> str:
    """An event in one line of words, as Compare shows where two runs part: its robot, phase, rule, light,
    move or target."""
    if ev.phase == "compute":
        rule = f" by {ev.rule_id}" if ev.rule_id else ""
        where = f", to move {ev.move.value}" if ev.move is not None else ", to stay"
        return f"robot {ev.robot} · Compute{rule} → light {ev.light}{where}"
    if ev.phase == "move" and ev.to is not None:
        where = f"robot {ev.robot} · Move → ({ev.to[0]}, {ev.to[1]}) on the grid"
        return where + (" COLLISION" if ev.collision else "")
    return f"robot {ev.robot} · Look"
