"""How an algorithm describes itself to the screen (optional; Mesa calls this a portrayal).

The visualiser knows no particular algorithm. It draws what the algorithm describes:

- a **legend**: a colour and a one-line meaning per light (:meth:`Portrayed.legend`);
- **overlays** of the whole run: marks in the global frame computed from the global configuration (the
  line K, the leader's frame, where the pattern will form) and the stage's name
  (:meth:`Portrayed.overlays`). They are for the screen only and never reach ``decide``;
- the **explanation** of one decision: the same :class:`~apf_viz.core.algorithm.Decision` as ``decide``
  plus the predicates its rule tested (symbol, value, meaning) and the regions it looked at, in the
  robot's own frame (:meth:`Portrayed.explain`), computed from the snapshot the decision used.

All three are optional: :func:`legend_of`, :func:`overlays_of` and :func:`explain` give every algorithm
defaults (a palette, no marks, a bare decision). Marks are plain frozen data, so the core stays free of
viser; ``ui/scene/`` draws them.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Literal, Protocol, TypeVar, runtime_checkable

from apf_viz.core.algorithm import Algorithm, Decision, Pattern
from apf_viz.core.grid import Point
from apf_viz.core.view import Snapshot

RGB = tuple[int, int, int]

# Colours for lights an algorithm does not describe: distinct, and readable on white.
PALETTE: tuple[RGB, ...] = (
    (150, 150, 150),
    (50, 110, 255),
    (255, 150, 0),
    (40, 170, 60),
    (220, 30, 30),
    (160, 80, 220),
    (0, 190, 200),
    (255, 80, 170),
    (140, 90, 40),
    (90, 90, 200),
)


@dataclass(frozen=True)
class LightStyle:
    """How a light looks and what it means. ``shape``: a disc, or a square for a light that must be told
    apart by more than its hue (by a colour-blind reader, or from the back of a room where a ring's
    colour bleeds into the disc's); every renderer draws it, canvas, legend, slide and figure."""

    color: RGB
    meaning: str = ""
    shape: Literal["disc", "square"] = "disc"


# ------------------------------------------------------------------------------------------------ marks
@dataclass(frozen=True)
class Line:
    """A horizontal (``axis="y"``: y = at) or vertical (``axis="x"``: x = at) line; ``at`` may be a
    half-integer (K can pass between two rows)."""

    axis: Literal["x", "y"]
    at: float
    label: str
    color: RGB | None = None  # None: the screen's default for lines


@dataclass(frozen=True)
class Band:
    """The strip lo ≤ coordinate ≤ hi across ``axis`` (``"x"``: columns, ``"y"``: rows)."""

    axis: Literal["x", "y"]
    lo: float
    hi: float
    label: str


@dataclass(frozen=True)
class HalfPlane:
    """The points whose ``axis`` coordinate is beyond ``at`` on ``side`` (+1: greater, −1: smaller);
    ``closed`` includes the boundary line."""

    axis: Literal["x", "y"]
    at: float
    side: Literal[1, -1]
    closed: bool
    label: str


@dataclass(frozen=True)
class Frame:
    """A coordinate system: its (0, 0) at ``origin`` and its +y along ``y_sign`` (+1 or −1)."""

    origin: Point
    y_sign: int
    label: str
    color: RGB | None = None


@dataclass(frozen=True)
class Cells:
    """A set of cells: ``style`` "placed" (final), "preview" (not yet placed: drawn dimmed) or "drawing"
    (a pattern being drawn in the studio)."""

    points: tuple[Point, ...]
    label: str
    style: Literal["placed", "preview", "drawing"] = "placed"


Mark = Line | Band | HalfPlane | Frame | Cells


@dataclass(frozen=True)
class Configuration:
    """The whole run at one moment, global frame: what overlays are computed from (never ``decide``)."""

    positions: tuple[Point, ...]
    lights: tuple[str, ...]
    pattern: Pattern
    start: tuple[Point, ...]


@dataclass(frozen=True)
class Overlays:
    """Marks over the whole run (global frame) and the stage the run is in."""

    marks: tuple[Mark, ...] = ()
    stage: str = ""


# ------------------------------------------------------------------------------------------ explanation
@dataclass(frozen=True)
class Predicate:
    """One test a rule made: its symbol in the paper's notation (``H_L^O(r) = ∅``), its value, and what
    it means for this robot."""

    symbol: str
    value: bool | int | str
    meaning: str


@dataclass(frozen=True)
class Explanation:
    """A decision with its evidence: the predicates tested, in order, and the regions looked at (the
    robot's own frame: the robot at (0, 0), its own +y up)."""

    decision: Decision
    predicates: tuple[Predicate, ...] = ()
    regions: tuple[Mark, ...] = ()


T = TypeVar("T")


@dataclass
class Evidence:
    """What a rule tests, collected while it decides. ``decide`` passes :data:`NO_EVIDENCE`, which keeps
    nothing, so ``explain`` and ``decide`` run the very same code and cannot disagree."""

    predicates: list[Predicate] = field(default_factory=list)
    regions: list[Mark] = field(default_factory=list)
    active = True  # False for NO_EVIDENCE: callers skip building what would be thrown away

    def test(self, symbol: str, value: T, meaning: str) -> T:
        """Record a predicate and return its value (use it inline: ``if ev.test(...):``)."""
        self.predicates.append(Predicate(symbol, value, meaning))  # type: ignore[arg-type]
        return value

    def region(self, mark: Mark) -> None:
        """Record a region the rule looked at (once, however often it looks)."""
        if mark not in self.regions:
            self.regions.append(mark)

    def explanation(self, decision: Decision) -> Explanation:
        """The decision with the evidence collected for it."""
        return Explanation(decision, tuple(self.predicates), tuple(self.regions))


class _NoEvidence(Evidence):
    active = False

    def test(self, symbol: str, value: T, meaning: str) -> T:
        """Keep nothing: the value, as ``decide`` needs it."""
        return value

    def region(self, mark: Mark) -> None:
        """Keep nothing."""
        pass


NO_EVIDENCE: Evidence = _NoEvidence()


# ------------------------------------------------------------------------------------------ pseudocode
@dataclass(frozen=True)
class CodeLine:
    """One line of an algorithm as its paper writes it. ``key`` names it ("A1.4"; a resolution's line
    "G2@A1.8"); ``number`` is the paper's line number ("" for a procedure's header or a resolution's
    line); ``depth`` its indentation. A resolution's line carries its name and why; a paper line a
    resolution rewrites is ``replaced`` (the screen strikes it through)."""

    key: str
    number: str
    depth: int
    text: str
    resolution: str = ""
    why: str = ""
    replaced: bool = False


@dataclass(frozen=True)
class CodeBlock:
    """One algorithm of the paper: its title and lines (procedure headers included)."""

    title: str
    lines: tuple[CodeLine, ...]


@dataclass(frozen=True)
class Pseudocode:
    """An algorithm's paper, line by line, and which line(s) each rule id acts on."""

    blocks: tuple[CodeBlock, ...]
    rules: dict[str, tuple[str, ...]]  # rule id (or a composite id in context) → line keys
    outside: dict[str, str] = field(default_factory=dict)  # rule ids with no line, each with the reason
    unreached: dict[str, str] = field(default_factory=dict)  # lines no rule reaches, each with the reason

    def lines_of(self, rule_id: str) -> tuple[str, ...]:
        """The lines a decision's rule id acts on: the composite id's own where given, else its parts'."""
        if rule_id in self.rules:
            return self.rules[rule_id]
        out: list[str] = []
        for part in rule_id.split("/"):
            out += [k for k in self.rules.get(part, ()) if k not in out]
        return tuple(out)

    def line(self, key: str) -> tuple[CodeBlock, int] | None:
        """The block holding a line and its index there."""
        for block in self.blocks:
            for i, line in enumerate(block.lines):
                if line.key == key:
                    return block, i
        return None

    def enclosing(self, key: str) -> tuple[str, ...]:
        """The conditions a line sits in, innermost first: each earlier line of smaller depth."""
        found = self.line(key)
        if found is None:
            return ()
        block, i = found
        depth, out = block.lines[i].depth, []
        for line in reversed(block.lines[:i]):
            if line.depth < depth and line.number:
                out.append(line.key)
                depth = line.depth
        return tuple(out)


# ------------------------------------------------------------------------------------------ the protocol
@runtime_checkable
class Portrayed(Protocol):
    """The optional half of an algorithm: how it describes itself. Any subset may be provided."""

    def legend(self) -> dict[str, LightStyle]:
        """Every light with its colour, shape and meaning (:func:`legend_of`)."""
        ...

    def overlays(self, config: Configuration) -> Overlays:
        """The marks over the whole run in this configuration, and its stage (:func:`overlays_of`)."""
        ...

    def stage(self, config: Configuration) -> str:
        """The stage of this configuration, without drawing the marks (:func:`stage_of`)."""
        ...

    def pseudocode(self) -> Pseudocode:
        """The algorithm's paper, line by line (:func:`pseudocode_of`)."""
        ...

    def explain(self, view: Snapshot, pattern: Pattern) -> Explanation:
        """The decision on this view with the predicates and regions it tested (:func:`explain`)."""
        ...

    def title(self) -> str:
        """The algorithm in words (:func:`title_of`)."""
        ...

    def rules(self) -> dict[str, str]:
        """Every rule id its decisions carry, with its words (:func:`rules_of`)."""
        ...


def title_of(algorithm: Algorithm) -> str:
    """The algorithm in words, for a room (Compare's titles): its own ``title`` where it gives one, else
    its registry name."""
    own = getattr(algorithm, "title", None)
    return own() if callable(own) else algorithm.name


def legend_of(algorithm: Algorithm) -> dict[str, LightStyle]:
    """Every light of the algorithm with its style: its own legend where it gives one, the palette
    elsewhere (in the order of ``lights``, so colours are stable)."""
    own = getattr(algorithm, "legend", None)
    given: dict[str, LightStyle] = dict(own()) if callable(own) else {}
    return {
        light: given.get(light, LightStyle(PALETTE[i % len(PALETTE)]))
        for i, light in enumerate(algorithm.lights)
    }


def overlays_of(algorithm: Algorithm, config: Configuration) -> Overlays:
    """The algorithm's overlays of this configuration, or none."""
    own = getattr(algorithm, "overlays", None)
    return own(config) if callable(own) else Overlays()


def pseudocode_of(algorithm: Algorithm) -> Pseudocode | None:
    """The algorithm's paper, line by line, where it gives one."""
    own = getattr(algorithm, "pseudocode", None)
    return own() if callable(own) else None


def stage_of(algorithm: Algorithm, config: Configuration) -> str:
    """The stage of this configuration, ``overlays_of(...).stage``: by the algorithm's own ``stage``
    where it gives one, which names the stage without drawing the marks (the timeline asks after every
    move)."""
    own = getattr(algorithm, "stage", None)
    return own(config) if callable(own) else overlays_of(algorithm, config).stage


def rules_of(algorithm: Algorithm) -> dict[str, str]:
    """Every rule id the algorithm's decisions carry, with its words (a lecture's ``until.rule`` names
    one); empty for an algorithm that lists none."""
    own = getattr(algorithm, "rules", None)
    return dict(own()) if callable(own) else {}


def explain(algorithm: Algorithm, view: Snapshot, pattern: Pattern) -> Explanation:
    """The algorithm's explanation of its decision on this view, or the bare decision."""
    own = getattr(algorithm, "explain", None)
    return own(view, pattern) if callable(own) else Explanation(algorithm.decide(view, pattern))


def in_frame(points: Sequence[Point], origin: Point, y_up: bool) -> tuple[Point, ...]:
    """Global points of a robot's local offsets (``origin`` its global position, ``y_up`` its flip)."""
    s = 1 if y_up else -1
    return tuple((origin[0] + x, origin[1] + s * y) for x, y in points)
