"""Colour words a lecture's stop says of the screen ("drawn grey", "the grey squares"), held against
what the screen draws at that stop: every colour the canvas shows is named as a person would name it
(grey, yellow, orange, ...), and a stop that says something is drawn in a colour nothing drawn has is
caught by ``lecture check`` (workbench/lecturer.py). Pure: reads a view, knows no viser."""

from __future__ import annotations

import colorsys
import re

from apf_viz.core.portrayal import RGB, Cells, Frame, Line
from apf_viz.workbench.palette import MARK_COLORS, PHASE_COLORS, TARGET_COLORS, region_color
from apf_viz.workbench.view_model import SessionView

__all__ = ["claimed_colours", "colour_name", "drawn_colours", "untrue_colours"]

COLOUR_WORDS = {
    "grey": "grey",
    "gray": "grey",
    "black": "black",
    "white": "white",
    "red": "red",
    "orange": "orange",
    "yellow": "yellow",
    "green": "green",
    "blue": "blue",
    "purple": "purple",
    "violet": "purple",
    "magenta": "magenta",
    "pink": "magenta",
    "brown": "brown",
}
"""A colour word of a stop's text, and the name it stands for (gray is grey, pink is magenta)."""

THING_WORDS = {
    "robot": "robot", "disc": "robot", "dot": "robot",
    "square": "square",
    "line": "line", "ray": "line", "arrow": "line",
    "ring": "ring",
    "target": "target", "cell": "target",
    "burst": "burst",
    "diamond": "diamond",
    "region": "region", "band": "region",
    "mark": "any", "frame": "any",
}  # fmt: skip
"""A thing a stop's text says is drawn in a colour, and the kind of mark it names."""
_COLOUR = "|".join(COLOUR_WORDS)
_THING = "|".join(rf"{word}s?" for word in THING_WORDS)
# "drawn grey", "shown in blue", "coloured orange" (anything); "grey squares", "a yellow ray" (that kind).
_CLAIM = re.compile(
    rf"\b(?:drawn|shown|painted|coloured|colored|marked)\s+(?:in\s+)?(?P<any>{_COLOUR})\b"
    rf"|\b(?P<colour>{_COLOUR})\s+(?P<thing>{_THING})\b",
    re.I,
)


def colour_name(rgb: RGB) -> str:
    """The name a person gives ``rgb``: black, white or grey when it has little colour, else its hue's
    (brown for a dark orange; magenta for the purples nearer red)."""
    r, g, b = (c / 255 for c in rgb)
    hue, lightness, _ = colorsys.rgb_to_hls(r, g, b)
    chroma = max(r, g, b) - min(r, g, b)
    if chroma < 0.15:
        return "black" if lightness < 0.2 else "white" if lightness > 0.9 else "grey"
    degrees = hue * 360
    if degrees < 15 or degrees >= 330:
        return "red"
    if degrees < 45:
        return "brown" if max(r, g, b) < 0.65 else "orange"
    if degrees < 70:
        return "yellow"
    if degrees < 170:
        return "green"
    if degrees < 255:
        return "blue"
    if degrees < 285:
        return "purple"
    return "magenta"


Drawn = dict[str, set[RGB]]
"""The colours drawn, by kind of mark (the kinds of :data:`THING_WORDS`)."""


def _add(drawn: Drawn, kind: str, *colours: RGB) -> None:
    drawn.setdefault(kind, set()).update(colours)


def _run_colours(view: SessionView, drawn: Drawn) -> None:
    """Every colour one run's picture holds: lights, phase rings, targets, the algorithm's marks."""
    for r in view.robots:
        style = view.legend.get(r.light)
        if style is not None:
            _add(drawn, "robot", style.color)
            if style.shape == "square":
                _add(drawn, "square", style.color)
        if r.phase in PHASE_COLORS and r.phase != "idle":
            _add(drawn, "ring", PHASE_COLORS[r.phase])
        if r.pending is not None:
            _add(drawn, "line", MARK_COLORS["pending"])
    if view.targets:
        _add(drawn, "target", TARGET_COLORS["placed"])
    for mark in view.overlays.marks:
        if isinstance(mark, Line):
            _add(drawn, "line", mark.color or MARK_COLORS["line"])
        elif isinstance(mark, Frame):
            _add(drawn, "line", mark.color or MARK_COLORS["frame"])
        elif isinstance(mark, Cells):
            _add(drawn, "target", TARGET_COLORS[mark.style])
    if view.collision is not None:
        _add(drawn, "burst", MARK_COLORS["collision"])
    if view.never_act:
        _add(drawn, "square", MARK_COLORS["never"])
    if view.last_actor is not None:
        _add(drawn, "ring", MARK_COLORS["last"])


def drawn_colours(view: SessionView) -> dict[str, set[str]]:
    """The names of the colours the screen draws for ``view``, by kind of mark ("any": every one): its
    run (and Compare's second run), the selected robot's ring and rays, its hidden robots, the lines to
    their hiders, its ghosts, and Why's regions."""
    drawn: Drawn = {}
    _run_colours(view, drawn)
    if view.compare is not None:
        _run_colours(view.compare, drawn)
    if view.selected is not None:
        _add(drawn, "ring", MARK_COLORS["selected"])
    if view.rays:
        _add(drawn, "line", MARK_COLORS["ray"])
    if view.hidden:
        _add(drawn, "robot", MARK_COLORS["hidden"])
        _add(drawn, "line", MARK_COLORS["hidden_line"])
    if view.ghosts:
        _add(drawn, "robot", MARK_COLORS["ghost"])
    if view.why is not None:
        _add(drawn, "region", *(region_color(i) for i in range(len(view.why.regions))))
    if view.diverged is not None:
        _add(drawn, "diamond", MARK_COLORS["diverged"])
    named = {kind: {colour_name(c) for c in colours} for kind, colours in drawn.items()}
    named["any"] = set().union(*named.values()) if named else set()
    return named


def claimed_colours(text: str) -> list[tuple[str, str, str]]:
    """What ``text`` says is drawn in a colour: (its words, the colour's name, the kind of mark: "any"
    for "drawn grey"), in the order said."""
    out: list[tuple[str, str, str]] = []
    for m in _CLAIM.finditer(text):
        if m.group("any"):
            claim = (m.group(0), COLOUR_WORDS[m.group("any").lower()], "any")
        else:
            thing = m.group("thing").lower().removesuffix("s")
            claim = (m.group(0), COLOUR_WORDS[m.group("colour").lower()], THING_WORDS[thing])
        if claim not in out:
            out.append(claim)
    return out


def untrue_colours(text: str, view: SessionView) -> list[str]:
    """What ``text`` says is drawn in a colour that nothing of that kind is drawn in for ``view``."""
    drawn = drawn_colours(view)
    out = []
    for words, colour, kind in claimed_colours(text):
        if colour not in drawn.get(kind, set()):
            shown = sorted(drawn.get(kind, set()))
            what = f"nothing {colour}" if kind == "any" else f"no {colour} {kind}"
            there = f"{', '.join(shown)} {'is' if len(shown) == 1 else 'are'}" if shown else "none is"
            out.append(f"its words say “{words}”; {what} is drawn at this stop ({there})")
    return out
