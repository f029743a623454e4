"""The pattern studio's tools as pure functions: cells in, cells out (no viser, no state). A drawing is a
list of distinct cells in the order they were drawn (Fit to k removes the last drawn first); every tool
returns a new list. Used by the Edit folder (workbench/editor.py) and by ``apf-viz pattern``."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence

from apf_viz.core.grid import Point

Cells = list[Point]
MAX_SIZE = 10_000  # a shape's size (radius, length, text length) beyond this is refused: a draft of millions

# A 3×5 bitmap font (upper-case letters and digits): rows top to bottom, "#" a cell. Small, so a word
# needs few robots: "APF" is 31 cells.
FONT: dict[str, tuple[str, ...]] = {
    "A": (".#.", "#.#", "###", "#.#", "#.#"), "B": ("##.", "#.#", "##.", "#.#", "##."),
    "C": (".##", "#..", "#..", "#..", ".##"), "D": ("##.", "#.#", "#.#", "#.#", "##."),
    "E": ("###", "#..", "##.", "#..", "###"), "F": ("###", "#..", "##.", "#..", "#.."),
    "G": (".##", "#..", "#.#", "#.#", ".##"), "H": ("#.#", "#.#", "###", "#.#", "#.#"),
    "I": ("###", ".#.", ".#.", ".#.", "###"), "J": ("..#", "..#", "..#", "#.#", ".#."),
    "K": ("#.#", "#.#", "##.", "#.#", "#.#"), "L": ("#..", "#..", "#..", "#..", "###"),
    "M": ("#.#", "###", "###", "#.#", "#.#"), "N": ("##.", "#.#", "#.#", "#.#", "#.#"),
    "O": (".#.", "#.#", "#.#", "#.#", ".#."), "P": ("##.", "#.#", "##.", "#..", "#.."),
    "Q": (".#.", "#.#", "#.#", "##.", ".##"), "R": ("##.", "#.#", "##.", "#.#", "#.#"),
    "S": (".##", "#..", ".#.", "..#", "##."), "T": ("###", ".#.", ".#.", ".#.", ".#."),
    "U": ("#.#", "#.#", "#.#", "#.#", "###"), "V": ("#.#", "#.#", "#.#", "#.#", ".#."),
    "W": ("#.#", "#.#", "###", "###", "#.#"), "X": ("#.#", "#.#", ".#.", "#.#", "#.#"),
    "Y": ("#.#", "#.#", ".#.", ".#.", ".#."), "Z": ("###", "..#", ".#.", "#..", "###"),
    "0": ("###", "#.#", "#.#", "#.#", "###"), "1": (".#.", "##.", ".#.", ".#.", "###"),
    "2": ("##.", "..#", ".#.", "#..", "###"), "3": ("##.", "..#", ".#.", "..#", "##."),
    "4": ("#.#", "#.#", "###", "..#", "..#"), "5": ("###", "#..", "##.", "..#", "##."),
    "6": (".##", "#..", "###", "#.#", "###"), "7": ("###", "..#", ".#.", ".#.", ".#."),
    "8": ("###", "#.#", "###", "#.#", "###"), "9": ("###", "#.#", "###", "..#", "##."),
    " ": ("...", "...", "...", "...", "..."),
}  # fmt: skip


class ShapeError(ValueError):
    """A shape that cannot be drawn (one line, for the person who asked)."""


def _size(n: int, what: str, least: int = 1) -> int:
    if not isinstance(n, int) or isinstance(n, bool) or not least <= n <= MAX_SIZE:
        raise ShapeError(f"{what} {n!r}: choose a whole number from {least} to {MAX_SIZE:,}")
    return n


def merged(cells: Sequence[Point], added: Iterable[Point]) -> Cells:
    """``cells`` then the new cells of ``added``, in order, without repeats."""
    seen, out = set(cells), list(cells)
    for p in added:
        if p not in seen:
            seen.add(p)
            out.append(p)
    return out


def removed(cells: Sequence[Point], gone: Iterable[Point]) -> Cells:
    """``cells`` without those in ``gone``, in order."""
    drop = set(gone)
    return [p for p in cells if p not in drop]


def toggled(cells: Sequence[Point], cell: Point) -> Cells:
    """``cells`` with ``cell`` removed if drawn, else added last."""
    return removed(cells, [cell]) if cell in cells else [*cells, cell]


def box(a: Point, b: Point) -> Cells:
    """Every cell of the rectangle with corners ``a`` and ``b`` (inclusive), row by row."""
    (x0, x1), (y0, y1) = sorted((a[0], b[0])), sorted((a[1], b[1]))
    _size((x1 - x0 + 1) * (y1 - y0 + 1), "rectangle of cells")
    return [(x, y) for y in range(y1, y0 - 1, -1) for x in range(x0, x1 + 1)]


def outline(a: Point, b: Point) -> Cells:
    """The border cells of the rectangle with corners ``a`` and ``b``."""
    (x0, x1), (y0, y1) = sorted((a[0], b[0])), sorted((a[1], b[1]))
    return [p for p in box(a, b) if p[0] in (x0, x1) or p[1] in (y0, y1)]


def line(a: Point, b: Point) -> Cells:
    """The digital line from ``a`` to ``b`` (Bresenham): every cell on it, both ends included."""
    (x0, y0), (x1, y1) = a, b
    dx, dy = abs(x1 - x0), -abs(y1 - y0)
    _size(max(dx, -dy) + 1, "line length")
    sx, sy = (1 if x1 > x0 else -1), (1 if y1 > y0 else -1)
    err, out = dx + dy, []
    while True:
        out.append((x0, y0))
        if (x0, y0) == (x1, y1):
            return out
        e2 = 2 * err
        if e2 >= dy:
            err += dy
            x0 += sx
        if e2 <= dx:
            err += dx
            y0 += sy


def ring(center: Point, radius: int) -> Cells:
    """A digital circle: the cells whose distance from ``center`` rounds to ``radius``, by angle."""
    r = _size(radius, "radius", 0)
    cx, cy = center
    cells = [
        (cx + x, cy + y)
        for x in range(-r - 1, r + 2)
        for y in range(-r - 1, r + 2)
        if round((x * x + y * y) ** 0.5) == r
    ]
    return sorted(cells, key=lambda p: _angle(p, center))


def disc(center: Point, radius: int) -> Cells:
    """A filled digital disc: the cells whose distance from ``center`` rounds to at most ``radius``."""
    r = _size(radius, "radius", 0)
    cx, cy = center
    return [
        (cx + x, cy + y)
        for y in range(r + 1, -r - 2, -1)
        for x in range(-r - 1, r + 2)
        if round((x * x + y * y) ** 0.5) <= r
    ]


def _angle(p: Point, center: Point) -> float:
    return math.atan2(p[1] - center[1], p[0] - center[0]) % (2 * math.pi)


def row(start: Point, length: int) -> Cells:
    """``length`` cells from ``start`` to the right."""
    n = _size(length, "length")
    return [(start[0] + i, start[1]) for i in range(n)]


def column(start: Point, length: int) -> Cells:
    """``length`` cells from ``start`` upwards."""
    n = _size(length, "length")
    return [(start[0], start[1] + i) for i in range(n)]


def staircase(start: Point, steps: int) -> Cells:
    """Steps up and to the right: (0, 0), (1, 0), (1, 1), (2, 1), … — 2·steps − 1 cells."""
    n = _size(steps, "steps")
    x, y = start
    out = [(x, y)]
    for i in range(1, n):
        out += [(x + i, y + i - 1), (x + i, y + i)]
    return out


def text(word: str, at: Point) -> Cells:
    """``word`` in the 3×5 font, its top-left cell at ``at``, a blank column between letters."""
    if not word or len(word) > 200:
        raise ShapeError("text: type 1 to 200 characters")
    unknown = sorted({c for c in word.upper() if c not in FONT})
    if unknown:
        raise ShapeError(f"text: no glyph for {''.join(unknown)!r} (letters A–Z, digits, spaces)")
    out: Cells = []
    for i, ch in enumerate(word.upper()):
        for dy, line_ in enumerate(FONT[ch]):
            out += [(at[0] + 4 * i + dx, at[1] - dy) for dx, c in enumerate(line_) if c == "#"]
    return out


def ascii_art(lines: Sequence[str], cell: str = "#") -> Cells:
    """Cells from text: ``cell`` marks a cell; the first line is the top row, (0, 0) its bottom-left.
    More than ``MAX_SIZE`` cells are refused before any is made (a 5 MB file of '#' is 5 million)."""
    count = sum(text_.count(cell) for text_ in lines)
    if count > MAX_SIZE:
        raise ShapeError(f"{count:,} {cell!r} cells, more than {MAX_SIZE:,}")
    height = len(lines)
    return [(x, height - 1 - y) for y, text_ in enumerate(lines) for x, c in enumerate(text_) if c == cell]


# ------------------------------------------------------------------------------------------ transforms
def translated(cells: Sequence[Point], dx: int, dy: int) -> Cells:
    """Every cell moved by (dx, dy), in order."""
    return [(x + dx, y + dy) for x, y in cells]


def _anchor(cells: Sequence[Point]) -> Point:
    return (min(x for x, _ in cells), min(y for _, y in cells)) if cells else (0, 0)


def mirrored(cells: Sequence[Point], axis: str) -> Cells:
    """Left–right (``axis="x"``: x is negated) or up–down (``"y"``), in place: the bounding box stays."""
    if not cells:
        return []
    xs, ys = [x for x, _ in cells], [y for _, y in cells]
    if axis == "x":
        return [(min(xs) + max(xs) - x, y) for x, y in cells]
    if axis == "y":
        return [(x, min(ys) + max(ys) - y) for x, y in cells]
    raise ShapeError(f"mirror {axis!r}: choose x (left–right) or y (up–down)")


def rotated(cells: Sequence[Point]) -> Cells:
    """A quarter turn anticlockwise about the drawing's bottom-left corner, which stays where it was."""
    if not cells:
        return []
    ax, ay = _anchor(cells)
    turned = [(-(y - ay), x - ax) for x, y in cells]
    bx, by = _anchor(turned)
    return [(x - bx + ax, y - by + ay) for x, y in turned]


def scaled(cells: Sequence[Point], factor: int = 2) -> Cells:
    """Each cell becomes a factor × factor block, about the drawing's bottom-left corner."""
    f = _size(factor, "scale", 1)
    ax, ay = _anchor(cells)
    if len(cells) * f * f > MAX_SIZE:
        raise ShapeError(f"scale ×{f}: {len(cells) * f * f:,} cells, more than {MAX_SIZE:,}")
    return merged(
        [],
        (
            (ax + (x - ax) * f + i, ay + (y - ay) * f + j)
            for x, y in cells
            for j in range(f)
            for i in range(f)
        ),
    )


def fitted(cells: Sequence[Point], k: int) -> tuple[Cells, str]:
    """The drawing with exactly ``k`` cells, and what was done: the last-drawn cells removed, or cells
    added along the outline (each new cell a free neighbour of the drawing, scanned from its top-left)."""
    n = _size(k, "robot count")
    if len(cells) == n:
        return list(cells), f"already {n} cells"
    if len(cells) > n:
        return list(cells[:n]), f"removed the {len(cells) - n} last-drawn cells"
    out, have = list(cells) or [(0, 0)], set(cells) or {(0, 0)}
    while len(out) < n:
        free = _neighbours_free(out, have)
        for p in free[: n - len(out)]:
            out.append(p)
            have.add(p)
    return out, f"added {n - len(cells)} cells along the outline"


def _neighbours_free(cells: Sequence[Point], taken: set[Point]) -> list[Point]:
    """The free cells beside ``cells``, from the top row down, left to right."""
    near = {(x + dx, y + dy) for x, y in cells for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1))}
    return sorted(near - taken, key=lambda p: (-p[1], p[0]))


def robots_fitted(
    robots: Sequence[Point], k: int, solvable: Callable[[Sequence[Point]], bool]
) -> tuple[Cells, str]:
    """``k`` robots: the last-placed ones removed, or new ones placed beside the others (the free cells
    from the top row down), each choice one that keeps the start ``solvable`` (Theorem 1) where one does."""
    n = _size(k, "pattern size")
    out = list(robots)
    if len(out) > n:
        while len(out) > n:
            # The last-placed robot whose removal leaves a solvable start (else the last one).
            i = next((i for i in reversed(range(len(out))) if solvable(out[:i] + out[i + 1 :])), len(out) - 1)
            del out[i]
        return out, f"removed {len(robots) - n} robots, the last placed"
    taken = set(out)
    while len(out) < n:
        free = _neighbours_free(out, taken) if out else [(0, 0)]
        cell = next((c for c in free if solvable([*out, c])), free[0])
        out.append(cell)
        taken.add(cell)
    added = n - len(robots)
    return out, f"added {added} robots beside the others" if added else f"already {n} robots"


def reflected(cells: Sequence[Point], twice_x: int | None, twice_y: int | None) -> Cells:
    """``cells`` with their mirror images (the studio's live mirror): about the vertical line x =
    ``twice_x``/2, the horizontal line y = ``twice_y``/2, or both (then four copies); halves allowed."""
    out = list(cells)
    if twice_x is not None:
        out += [(twice_x - x, y) for x, y in out]
    if twice_y is not None:
        out += [(x, twice_y - y) for x, y in out]
    return merged([], out)


FILL_AREA = 250_000
"""The flood fill searches at most this many cells (the drawing's box): a fill is a gesture, not a job."""


def flood_filled(cells: Sequence[Point], seed: Point) -> Cells:
    """The empty cells 4-connected to ``seed`` (which is empty), bounded by ``cells``: the region a paint
    bucket fills. Refused when the region is open (it reaches outside the drawing's box: on an infinite
    grid it would never end), or the box is larger than :data:`FILL_AREA`."""
    taken = set(cells)
    if seed in taken:
        raise ShapeError(f"{seed} is drawn already: the fill fills an empty region (the eraser empties)")
    if not taken:
        raise ShapeError("nothing drawn to bound the fill: draw a closed outline first")
    x0, x1 = min(x for x, _ in taken), max(x for x, _ in taken)
    y0, y1 = min(y for _, y in taken), max(y for _, y in taken)
    open_region = f"the region at {seed} is open (it reaches outside the drawing): close its outline first"
    if not (x0 < seed[0] < x1 and y0 < seed[1] < y1):
        raise ShapeError(open_region)
    if (x1 - x0 + 1) * (y1 - y0 + 1) > FILL_AREA:
        raise ShapeError(f"the drawing's box is larger than {FILL_AREA:,} cells: too large to fill")
    region, seen, frontier = [], {seed}, [seed]
    while frontier:
        x, y = frontier.pop()
        if not (x0 < x < x1 and y0 < y < y1):
            raise ShapeError(open_region)
        region.append((x, y))
        for p in ((x + 1, y), (x - 1, y), (x, y + 1), (x, y - 1)):
            if p not in taken and p not in seen:
                seen.add(p)
                frontier.append(p)
    return region


def inside(cells: Sequence[Point], a: Point, b: Point) -> Cells:
    """The cells of ``cells`` in the box with corners ``a`` and ``b`` (a selection)."""
    (xa, ya), (xb, yb) = a, b
    x0, x1, y0, y1 = min(xa, xb), max(xa, xb), min(ya, yb), max(ya, yb)
    return [(x, y) for x, y in cells if x0 <= x <= x1 and y0 <= y <= y1]
