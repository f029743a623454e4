"""A run of one's own, branched from the shared run as it is (Try it yourself, Export page): no viser."""

from __future__ import annotations

from apf_viz.workbench.compare import Twin
from apf_viz.workbench.session import Session

EXTRA_EVENTS = 100_000  # a run of one's own goes at most this many events past where it branched


def branch(shared: Session) -> Session:
    """A run of one's own: the shared run's configuration, played to the shared run's step by the same
    step records (the same events, lights and positions), then free to go its own way."""
    with shared.lock:
        config = shared.config
        engine = shared.engine
        records = [engine.history.steps.record(i) for i in range(engine.step_index)]
        events = engine.state.events
        plugins = shared.run.plugins
        numbers = shared.numbers
        compared = shared.screen.twin.algorithm if shared.screen.twin is not None else None
    own = Session.from_config(config.but(event_cap=events + EXTRA_EVENTS), plugins)
    if compared is not None:  # the lecture's Compare too: the copy's second run follows the copy
        own.screen.twin = Twin(compared, plugins)
    for record in records:
        own.engine.apply(record)
    own.numbers = numbers
    return own
