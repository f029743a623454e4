"""A drawing as a plain ``tikzpicture`` (pdflatex with the tikz package and nothing else: colours are
defined with ``\\definecolor``, which TikZ's own xcolor provides), one cell = :data:`UNIT`."""

from __future__ import annotations

import math

from apf_viz.figure.drawing import RGB, Drawing
from apf_viz.workbench.palette import MARK_COLORS

UNIT = "0.5cm"
_SPECIAL = {
    "\\": r"\textbackslash{}",
    "_": r"\_",
    "&": r"\&",
    "%": r"\%",
    "$": r"\$",
    "#": r"\#",
    "{": r"\{",
    "}": r"\}",
    "^": r"\^{}",
    "~": r"\~{}",
}


def tex_math(name: str) -> str:
    """A robot's name as the paper sets it: ``r``, ``r_0``."""
    return name.replace("₀", "_0")


def tex_text(text: str) -> str:
    """Plain text, safe in LaTeX (a label such as ``L_1`` keeps its underscore); what pdflatex's default
    encoding lacks is spelt in ASCII."""
    plain = text.replace("′", "'").replace("·", "-").replace("→", "->").replace("◆", "").replace("−", "-")
    plain = plain.replace("“", "``").replace("”", "''").replace("’", "'").replace("₀", "_0")
    safe = "".join(_SPECIAL.get(c, c) for c in plain)
    return safe.encode("ascii", "replace").decode("ascii")


class _Colours:
    """Each colour used, named once (``\\definecolor``) at the top of the picture."""

    def __init__(self) -> None:
        self.names: dict[RGB, str] = {}

    def __call__(self, c: RGB) -> str:
        return self.names.setdefault(c, f"apf{len(self.names)}")

    def definitions(self) -> list[str]:
        return [rf"\definecolor{{{n}}}{{RGB}}{{{c[0]},{c[1]},{c[2]}}}" for c, n in self.names.items()]


def to_tikz(d: Drawing) -> str:
    colour = _Colours()
    x0, y0, x1, y1 = d.box
    body = [_grid(x0, y0, x1, y1)]
    cells = colour(d.cells_color)
    body += [
        rf"\fill[{cells}] ({x - 0.4:g},{y - 0.4:g}) rectangle ({x + 0.4:g},{y + 0.4:g});" for x, y in d.cells
    ]
    body += _marks(d, colour)
    body += _robots(d, colour)
    body += _legend(d, colour, x1 + 0.8, y1 - 0.5)
    if d.caption:
        at = f"({x0:g},{y0 - 0.3:g})"
        body.append(rf"\node[below right, font=\small, text width=12cm] at {at} {{{tex_text(d.caption)}}};")
    head = rf"\begin{{tikzpicture}}[x={UNIT}, y={UNIT}]"
    return "\n".join([head, *colour.definitions(), *body, r"\end{tikzpicture}"]) + "\n"


def _marks(d: Drawing, colour: _Colours) -> list[str]:
    """The algorithm's lines and frames, and the selected robot's rays."""
    x0, y0, x1, y1 = d.box
    out = []
    for axis, at, label, c in d.lines:
        ends = f"({at:g},{y0:g}) -- ({at:g},{y1:g})" if axis == "x" else f"({x0:g},{at:g}) -- ({x1:g},{at:g})"
        place = "above right" if axis == "x" else "above left"
        node = rf"node[{place}, font=\scriptsize, black] {{{tex_text(label)}}}"
        out.append(rf"\draw[{colour(c)}, line width=1.2pt] {ends} {node};")
    for (ox, oy), s, label, c in d.frames:
        arms = f"({ox + 2},{oy}) -- ({ox},{oy}) -- ({ox},{oy + 2 * s})"
        out.append(rf"\draw[{colour(c)}, line width=1.2pt, <->] {arms};")
        out.append(rf"\node[right, font=\scriptsize] at ({ox + 2.1},{oy}) {{{tex_text(label)}}};")
    ray = colour(MARK_COLORS["ray"])
    out += [rf"\draw[{ray}, line width=1pt] ({a[0]},{a[1]}) -- ({b[0]},{b[1]});" for a, b in d.rays]
    return out


def _grid(x0: float, y0: float, x1: float, y1: float) -> str:
    """A line between every two cells (cells are centred on integer points)."""
    xs = [k + 0.5 for k in range(math.floor(x0), math.ceil(x1))]
    ys = [k + 0.5 for k in range(math.floor(y0), math.ceil(y1))]
    lines = [f"({x:g},{y0:g}) -- ({x:g},{y1:g})" for x in xs] + [
        f"({x0:g},{y:g}) -- ({x1:g},{y:g})" for y in ys
    ]
    return r"\draw[black!12, line width=0.3pt] " + " ".join(lines) + ";"


def _robots(d: Drawing, colour: _Colours) -> list[str]:
    outline = colour(MARK_COLORS["outline"])
    out = []
    for disc in d.robots:
        x, y = disc.at
        style = rf"fill={colour(disc.color)}, draw={outline}, line width=0.6pt"
        if disc.square:
            box = f"({x - 0.34:g},{y - 0.34:g}) rectangle ({x + 0.34:g},{y + 0.34:g})"
            out.append(rf"\filldraw[{style}] {box};")
        else:
            out.append(rf"\filldraw[{style}] ({x},{y}) circle (0.34);")
        # \footnotesize (8 pt) at a cell of 0.5 cm: a number a reader reads at the figure's printed size
        out.append(rf"\node[font=\footnotesize] at ({x + 0.5},{y + 0.5}) {{{disc.number}}};")
    named = colour(MARK_COLORS["named"])
    for (x, y), name in d.named:  # the robot the caption names: ringed, its name at its lower left
        out.append(rf"\draw[{named}, line width=1.2pt] ({x},{y}) circle (0.48);")
        out.append(rf"\node[font=\small\bfseries, {named}] at ({x - 0.6},{y - 0.6}) {{${tex_math(name)}$}};")
    veil, edge = colour(MARK_COLORS["hidden"]), colour(MARK_COLORS["hidden_line"])
    style = rf"fill={veil}, fill opacity=0.8, draw={edge}, dashed"
    out += [rf"\filldraw[{style}] ({x},{y}) circle (0.34);" for x, y in d.hidden]
    if d.selected is not None:
        out.append(rf"\draw[black, line width=1pt] ({d.selected[0]},{d.selected[1]}) circle (0.5);")
    return out


def _legend(d: Drawing, colour: _Colours, left: float, top: float) -> list[str]:
    out, y = [], top
    for name, c in d.legend:
        shape = (
            f"({left - 0.25:g},{y - 0.25:g}) rectangle ({left + 0.25:g},{y + 0.25:g})"
            if name in d.square_lights
            else f"({left:g},{y:g}) circle (0.25)"
        )
        out.append(rf"\filldraw[fill={colour(c)}, draw=black!70] {shape};")
        out.append(rf"\node[right, font=\scriptsize] at ({left + 0.4:g},{y:g}) {{{tex_text(name)}}};")
        y -= 0.8
    for name, c in d.marks_legend:
        box = f"({left - 0.25:g},{y - 0.25:g}) rectangle ({left + 0.25:g},{y + 0.25:g})"
        out.append(rf"\fill[{colour(c)}] {box};")
        out.append(rf"\node[right, font=\scriptsize] at ({left + 0.4:g},{y:g}) {{{tex_text(name)}}};")
        y -= 0.8
    return out
