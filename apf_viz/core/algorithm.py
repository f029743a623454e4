"""The seam between the engine and an algorithm: a pure function of one robot's snapshot.

An algorithm sees a :class:`~apf_viz.core.view.Snapshot` (and the target pattern, its input) and returns a
:class:`Decision`: the new light, an optional unit move in the robot's *local* frame, and the rule that
fired, in the algorithm's own words and as a stable id (the visualiser captions them; traces record
them). The engine alone maps
the move to the global frame, applies it later (possibly on a stale snapshot), and detects collisions.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Protocol, runtime_checkable

from apf_viz.core.grid import Direction, Point
from apf_viz.core.view import Snapshot

Pattern = tuple[Point, ...]

Box = tuple[int | None, int | None, int | None, int | None]
"""``(x0, x1, y0, y1)``: the closed box x0 ≤ dx ≤ x1, y0 ≤ dy ≤ y1 in the robot's own frame; None is
unbounded on that side."""


@dataclass(frozen=True, slots=True)
class Watch:
    """What a "same light, stay" decision depended on: the robot's answer stays "same light, stay" on every
    later view that agrees with this one inside every region below and in which no robot showing one of
    ``lights`` has come into sight. An algorithm's promise, in its own frame; the engine uses it to skip
    re-deciding idle robots that no move or light change concerns (docs/ALGORITHM.md, "Watches").

    Every region is convex and contains the robot itself, so whether a robot inside it is visible
    depends only on the robots inside it: the engine needs no view to tell that a region is untouched.

    Attributes:
        boxes: closed axis-aligned boxes (:data:`Box`), each containing the origin.
        segments: closed segments from the robot (the origin) to these offsets, e.g. to the robot whose
            presence the decision relied on (a witness).
        any_of: witnesses of a fact any of several robots shows (e.g. "a robot still forming"), by
            offset: the answer stays while any one of them stays in sight with its light, inside
            ``within``, wherever it moves (the engine follows each witness, and its segment, by robot).
        lights: a robot showing one of these lights coming into sight (by moving, by no longer being
            hidden, or by taking the light) may change the answer.
        seen_at: offsets where a robot of a watched light already was in sight: one seen there again is
            not news (e.g. the leader, hidden for a while by a passing robot, then revealed).
        occupied: boxes (:data:`Box`) of which at least one must keep holding a robot, whoever it is and
            however it moves inside (e.g. "some robot is between my row and the leader's"). The engine
            counts robots, not visible ones: the algorithm uses such a box only where the two agree,
            i.e. where every segment from the robot to a point of the box runs inside the box (a robot
            in it is then visible, or hidden behind another robot in it).
    """

    boxes: tuple[Box, ...] = ()
    segments: tuple[Point, ...] = ()
    any_of: tuple[Point, ...] = ()
    lights: frozenset[str] = frozenset()
    seen_at: tuple[Point, ...] = ()
    occupied: tuple[Box, ...] = ()
    within: Box | None = None  # where an any-of witness may move and still count (None: anywhere)


NOTHING = Watch()
"""The watch of a decision that depends on nothing it sees (e.g. a robot that is done)."""


@dataclass(frozen=True, slots=True)
class Decision:
    """The output of one Compute. ``move`` is in the robot's local frame; None means stay.

    ``watch`` (optional, only on "same light, stay") narrows what the engine must watch before asking
    again; None means any change in the robot's view may matter.

    ``stride`` (optional, only on a move that keeps the light) is the algorithm's promise that this very
    decision is its answer again on every view this one becomes after the robot's own next
    ``stride − 1`` moves when nothing else changes: the same robots in sight, each offset shifted by the
    robot's own progress (``j·move`` after j moves, 1 ≤ j < stride). The engine may then apply those
    ``stride`` cycles at once where the scheduler has no choice (:mod:`apf_viz.core.fast_forward`);
    1 promises nothing beyond this cycle."""

    light: str
    move: Direction | None = None
    rule: str = ""
    rule_id: str = ""  # stable, for tests and traces (e.g. "A1.off.terminal"); ``rule`` is the prose
    watch: Watch | None = field(default=None, compare=False, repr=False)
    stride: int = field(default=1, compare=False, repr=False)

    def is_noop(self, current_light: str) -> bool:
        """True when acting on this decision changes nothing: same light, no move."""
        return self.move is None and self.light == current_light

    def named(self, rule: str, rule_id: str) -> Decision:
        """The same decision under another rule's words and id (``dataclasses.replace`` costs a few µs,
        and the traveller's decision is composed like this at each of its steps)."""
        return Decision(self.light, self.move, rule, rule_id, self.watch, self.stride)


@runtime_checkable
class Algorithm(Protocol):
    """What a plug-in algorithm provides.

    Attributes:
        name: the registry name (``apf-viz run --algorithm NAME``).
        lights: every light it may set; ``lights[0]`` is every robot's light at the start.
    """

    # Read-only members: a class attribute (``lights = ("off", "done")``) or a property provides them.
    @property
    def name(self) -> str:
        """The registry name (``apf-viz run --algorithm NAME``)."""
        ...

    @property
    def lights(self) -> tuple[str, ...]:
        """Every light it may set; ``lights[0]`` is every robot's light at the start."""
        ...

    def decide(self, view: Snapshot, pattern: Pattern) -> Decision:
        """Compute: must be deterministic and depend on nothing but its arguments."""
        ...
