"""The seam between the engine and an algorithm: a pure function of one robot's snapshot.

An algorithm sees a :class:`~apf_viz.core.view.Snapshot` (and the target pattern, its input) and returns a
:class:`Decision`: the new light, an optional unit move in the robot's *local* frame, and the rule that
fired, in the algorithm's own words and as a stable id (the visualiser captions them; traces record
them). The engine alone maps
the move to the global frame, applies it later (possibly on a stale snapshot), and detects collisions.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol, runtime_checkable

from apf_viz.core.grid import Direction, Point
from apf_viz.core.view import Snapshot

Pattern = tuple[Point, ...]


@dataclass(frozen=True, slots=True)
class Decision:
    """The output of one Compute. ``move`` is in the robot's local frame; None means stay."""

    light: str
    move: Direction | None = None
    rule: str = ""
    rule_id: str = ""  # stable, for tests and traces (e.g. "A1.off.terminal"); ``rule`` is the prose

    def is_noop(self, current_light: str) -> bool:
        """True when acting on this decision changes nothing: same light, no move."""
        return self.move is None and self.light == current_light


@runtime_checkable
class Algorithm(Protocol):
    """What a plug-in algorithm provides.

    Attributes:
        name: the registry name (``apf-viz run --algorithm NAME``).
        lights: every light it may set; ``lights[0]`` is every robot's light at the start.
    """

    name: str
    lights: tuple[str, ...]

    def decide(self, view: Snapshot, pattern: Pattern) -> Decision:
        """Compute: must be deterministic and depend on nothing but its arguments."""
        ...
