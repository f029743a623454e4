"""Merged-light variants: what if two of an algorithm's lights were one colour?

``BASE+merge(a=b)`` (several pairs: ``+merge(a=b,c=d)``) is BASE with lights a and b shown as one colour,
named a. The model stays honest, because a light is all the memory a robot has and all another robot can
read of it:

- every robot sees the merged colour wherever a or b would be shown, its own light included;
- a decision of BASE that sets b shows a: the robot and every robot that sees it read a from then on;
- BASE decides on those views unchanged: the merged colour *reads as a*, the first-named light. So
  ``merge(leader1=decider)`` asks whether the algorithm survives its deciders being taken for leader1
  robots (and their own reading of themselves as leader1), and ``merge(decider=leader1)`` the reverse.

The variant's ``lights`` are BASE's with each b left out, the merged colour in the place of whichever
of a and b comes first (a merged start light, BASE's first, is every robot's start, shown as a). A merge
is refused with one line where it is meaningless: a light with itself, a light BASE does not have, a
light in two merges, or a merge of a merge.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from dataclasses import replace

from apf_viz.core.algorithm import Algorithm, Decision, Pattern
from apf_viz.core.portrayal import (
    Configuration,
    Explanation,
    LightStyle,
    Overlays,
    Pseudocode,
    explain,
    legend_of,
    overlays_of,
    pseudocode_of,
    stage_of,
    title_of,
)
from apf_viz.core.view import Snapshot

MARKER = "+merge("
_PAIR = re.compile(r"\s*([A-Za-z0-9_-]+)\s*=\s*([A-Za-z0-9_-]+)\s*")


def merged_name(base: str, pairs: Sequence[tuple[str, str]]) -> str:
    """``BASE+merge(a=b,…)``, the name :func:`split_name` reads back; ``base`` itself without pairs."""
    merges = ",".join(f"{a}={b}" for a, b in pairs)
    return f"{base}{MARKER}{merges})" if merges else base


def split_name(name: str) -> tuple[str, list[tuple[str, str]]] | None:
    """``BASE+merge(a=b,…)`` as (BASE, [(a, b), …]); None for a name without a merge. Raises
    ``ValueError`` (one line) for a merge written wrong."""
    base, marker, rest = name.partition(MARKER)
    if not marker:
        return None
    if not base:
        raise ValueError(
            f"{name[:80]!r}: a merge follows an algorithm's name, e.g. apf-opaque-grid+merge(a=b)"
        )
    if not rest.endswith(")") or MARKER in rest:
        raise ValueError(f"{name[:80]!r}: write one +merge(a=b) (pairs separated by commas) at the end")
    pairs = []
    for part in rest[:-1].split(","):
        m = _PAIR.fullmatch(part)
        if m is None:
            raise ValueError(f"{name[:80]!r}: {part.strip()[:40]!r} is not a pair light=light")
        pairs.append((m.group(1), m.group(2)))
    return base, pairs


class MergedLights:
    """An algorithm with some of its lights shown as one colour (see the module's docstring)."""

    def __init__(self, base: Algorithm, pairs: Sequence[tuple[str, str]]) -> None:
        self.base = base
        self._as: dict[str, str] = {}
        for a, b in pairs:
            for light in (a, b):
                if light not in base.lights:
                    raise ValueError(
                        f"cannot merge {a}={b}: {base.name} has no light {light!r} "
                        f"(its lights: {', '.join(base.lights)})"
                    )
            if a == b:
                raise ValueError(f"cannot merge {a}={b}: a light is one colour already")
            if a in self._as or b in self._as or b in self._as.values() or a in self._as.values():
                raise ValueError(f"cannot merge {a}={b}: each light may be in one merge only")
            self._as[b] = a
        self.pairs = tuple((a, b) for b, a in self._as.items())
        self._start_hidden = base.lights[0] in self._as
        self.lights: tuple[str, ...] = tuple(dict.fromkeys(self.shown(light) for light in base.lights))
        self.name = merged_name(base.name, self.pairs)

    def shown(self, light: str) -> str:
        """The colour a light is shown as."""
        return self._as.get(light, light)

    def decide(self, view: Snapshot, pattern: Pattern) -> Decision:
        return self._merged(self.base.decide(view, pattern))

    def decide_telling(self, view: Snapshot, pattern: Pattern) -> tuple[Decision, bool]:
        """:meth:`decide`, and whether the merge is at work in it: BASE set a light that shows as another,
        or BASE's start light is hidden (every robot shows the merged colour from the start, so every
        decision is taken among robots that may not be what they show). The light lab counts these: a
        merge never at work is untested, not survived."""
        decision = self.base.decide(view, pattern)
        return self._merged(decision), self._start_hidden or decision.light in self._as

    def _merged(self, decision: Decision) -> Decision:
        watch = decision.watch
        if watch is not None and watch.lights & self._as.keys():
            watch = replace(watch, lights=frozenset(map(self.shown, watch.lights)))
        if decision.light in self._as:
            # The rule names the light the algorithm meant; the screen and the trace say what shows.
            shown = self.shown(decision.light)
            rule = f"{decision.rule} ({decision.light} is shown as {shown}: merged)" if decision.rule else ""
            return replace(decision, light=shown, watch=watch, rule=rule)
        if watch is not decision.watch:
            return replace(decision, watch=watch)
        return decision

    # ------------------------------------------------------------------ how it portrays itself
    def legend(self) -> dict[str, LightStyle]:
        """BASE's legend; a merged colour is a's style, its meaning naming both lights."""
        base = legend_of(self.base)
        out = {}
        for light in self.lights:
            style = base[light]
            merged = [b for b, a in self._as.items() if a == light]
            if merged:
                style = LightStyle(
                    style.color, f"{light} = {', '.join(merged)} (merged): {style.meaning}", style.shape
                )
            out[light] = style
        return out

    def overlays(self, config: Configuration) -> Overlays:
        return overlays_of(self.base, config)

    def stage(self, config: Configuration) -> str:
        return stage_of(self.base, config)

    def pseudocode(self) -> Pseudocode | None:
        return pseudocode_of(self.base)

    def title(self) -> str:
        merges = ", ".join(f"{b} shown as {a}" for a, b in self.pairs)
        return f"{title_of(self.base)}, {merges}"

    def explain(self, view: Snapshot, pattern: Pattern) -> Explanation:
        found = explain(self.base, view, pattern)
        return replace(found, decision=self._merged(found.decision))


class AtWork:
    """A merged variant that counts the decisions in which its merge is at work
    (:meth:`MergedLights.decide_telling`). What an engine or the explorer asks it is what is counted:
    each distinct view once where they memoise, and also the probes whose answer the merge turned into
    "same light, stay" (call shown as off, for a robot that is off: it never even Computes)."""

    def __init__(self, variant: MergedLights) -> None:
        self.variant = variant
        self.name = variant.name
        self.lights = variant.lights
        self.count = 0

    def decide(self, view: Snapshot, pattern: Pattern) -> Decision:
        decision, at_work = self.variant.decide_telling(view, pattern)
        self.count += at_work
        return decision


def merged_algorithm(name: str, get: Callable[[str], Algorithm]) -> Algorithm | None:
    """The variant a merged name asks for (``get`` resolves BASE), or None for a name without a merge."""
    parts = split_name(name)
    if parts is None:
        return None
    base, pairs = parts
    return MergedLights(get(base), pairs)
