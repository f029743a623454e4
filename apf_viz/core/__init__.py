"""The pure simulation core: grid, frames, views, engine, schedulers, history, files. No viser here."""

from apf_viz.core.algorithm import Algorithm, Decision, Pattern
from apf_viz.core.engine import Engine, EngineError
from apf_viz.core.engine_state import Phase
from apf_viz.core.grid import Direction, Point, visible_from
from apf_viz.core.history import Event, StepRecord
from apf_viz.core.schedulers import SCHEDULERS, make_scheduler
from apf_viz.core.view import Seen, Snapshot

__all__ = [
    "SCHEDULERS",
    "Algorithm",
    "Decision",
    "Direction",
    "Engine",
    "EngineError",
    "Event",
    "Pattern",
    "Phase",
    "Point",
    "Seen",
    "Snapshot",
    "StepRecord",
    "make_scheduler",
    "visible_from",
]
