"""Where text goes on the canvas: a label keeps its size on screen, so it is laid out in cells for
the framed zoom, clear of robots, their numbers and other labels."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from apf_viz.ui.scene.style import LABEL_SCALE, STALE_MARK, Bounds


def number_labels(
    pts: list[list[float]],
    numbers: bool,
    stale: tuple[int, ...],
    diverged: int | None = None,
    next_phase: tuple[str, ...] = (),
) -> list[tuple[str, tuple[float, float, float]]]:
    """One label per robot at its upper right, so that nothing said of a robot can be read as a
    neighbour's or pile onto another label: its number; "stale" for a robot holding a stale snapshot;
    "diverges here" for the robot where Compare's two runs part; under Manual its next phase ("→ look",
    given by the caller only while numbers are shown). Without numbers, the words alone in the same
    place."""
    holding = set(stale)
    labels = []
    for i, (x, y) in enumerate(pts):
        words = [str(i)] if numbers else []
        if i < len(next_phase) and next_phase[i]:
            words.append(f"→ {next_phase[i]}")
        if i in holding:
            words.append(STALE_MARK)
        if i == diverged:
            words.append("diverges here")
        if words:
            labels.append((" ".join(words), (x + 0.25, y + 0.3, 0.7)))
    return labels


Anchor = str  # viser's label anchor: which point of the text sits at the label's position

LabelSpec = tuple  # (text, (x, y, z)) or (text, (x, y, z), anchor): a label as the canvas draws it


def robot_spots(x: float, y: float, width: float, height: float) -> list[tuple[float, float, Anchor, float]]:
    """Where a label may go so that it touches the thing at (x, y) (a robot, a ghost): its upper right
    first (where a number is looked for), then the other corners, its sides, above, below. Each as (the
    lower left of the box the label may take, its bottom, viser's anchor, the anchor's x): a label on the
    left is anchored by its right end and one above or below by its middle, so that its text, never
    wider than ``width``, ends on the robot whatever its real width."""
    left, right, mid = x - 0.25 - width, x + 0.25, x - width / 2
    return [
        (right, y + 0.3, "bottom-left", right), (right, y - 0.3 - height, "bottom-left", right),
        (left, y + 0.3, "bottom-right", x - 0.25), (left, y - 0.3 - height, "bottom-right", x - 0.25),
        (x + 0.45, y - height / 2, "bottom-left", x + 0.45),
        (x - 0.45 - width, y - height / 2, "bottom-right", x - 0.45),
        (mid, y + 0.45, "bottom-center", x), (mid, y - 0.45 - height, "bottom-center", x),
    ]  # fmt: skip


def place_near(
    text: str,
    at: tuple[float, float],
    height: float,
    taken: list[Bounds],
    discs: Sequence[Bounds] = (),
    left_edge: float = -float("inf"),
) -> tuple[tuple[float, float], Anchor, Bounds]:
    """The place of a label touching the thing at ``at``: the first of :func:`robot_spots` over no label
    (``taken``) and no other robot (``discs``); else over no label; else the one that covers least. A
    plain number keeps its upper right over a neighbour (it is looked for there) and moves only off
    another label. Returns (its position, its anchor, the box it may take)."""
    width = label_width(text, height)
    best: tuple[tuple[float, float], Anchor, Bounds] | None = None
    least = (float("inf"), float("inf"))
    spots = robot_spots(at[0], at[1], width, height)
    for sx, sy, anchor, ax in spots:
        box = label_box(text, (sx, sy, sx), height)
        if box[0] < left_edge:
            continue
        covered = 0.0 if text.isdigit() else sum(_overlap_area(box, d) for d in discs)
        cost = (sum(_overlap_area(box, t) for t in taken), covered)
        if cost < least:
            least, best = cost, ((ax, sy), anchor, box)
        if cost == (0.0, 0.0):
            break
    if best is None:  # every place is past the left edge: the first, whatever it covers
        sx, sy, anchor, ax = spots[0]
        best = ((ax, sy), anchor, label_box(text, (sx, sy, sx), height))
    return best


def robot_discs(pts) -> list[Bounds]:
    """Each robot's disc as a box, for a label to keep clear of."""
    return [(x - 0.4, y - 0.4, x + 0.4, y + 0.4) for x, y in pts]


def spread(
    labels: list[tuple[str, tuple[float, float, float]]],
    pts: list[list[float]],
    height: float,
    left_edge: float = -float("inf"),
    taken: Sequence[Bounds] = (),
) -> list[LabelSpec]:
    """Robots' labels (:func:`number_labels`, at each robot's upper right) moved, where their own place
    covers another label or robot, to another place touching their robot (:func:`place_near`). The plain
    numbers first, so that a longer label gives way to them. ``height``: a label's height in cells;
    ``left_edge``: how far left a framed camera shows (a label moved past it would not be seen);
    ``taken``: labels already on the canvas (another run's), kept clear of as well. Each label comes back
    with its anchor; :func:`spec_box` gives the box each may take."""
    discs = robot_discs(pts)
    order = sorted(range(len(labels)), key=lambda i: not labels[i][0].isdigit())  # plain numbers first
    boxes = list(taken)
    placed: dict[int, LabelSpec] = {}
    for i in order:
        text, (x0, y0, z) = labels[i]
        x, y = x0 - 0.25, y0 - 0.3  # the robot it belongs to
        others = [d for d in discs if not (d[0] < x < d[2] and d[1] < y < d[3])]  # not its own robot
        (ax, ay), anchor, box = place_near(text, (x, y), height, boxes, others, left_edge)
        boxes.append(box)
        placed[i] = (text, (ax, ay, z), anchor)
    return [placed[i] for i in range(len(labels))]


def spec_box(spec: LabelSpec, height: float) -> Bounds:
    """The box a label laid out by :func:`spread` (or at its lower left, without an anchor) may take."""
    text, (x, y, _), *rest = spec
    anchor = rest[0] if rest else "bottom-left"
    width = label_width(text, height)
    left = x - width if anchor.endswith("right") else x - width / 2 if anchor.endswith("center") else x
    return (left, y, left + width, y + height)


# A label's box on screen at LABEL_SCALE (viser's label renderer: the font's line height, 1.15 em for the
# sans-serif fonts it uses, and a fifth of it as padding): 12 px × LABEL_SCALE × 1.15 × 1.2, 20.0 px
# measured at a scale of 1.2; and a pixel of air: labels laid out touching would be read as one.
LABEL_TEXT_PX = 20.0 * LABEL_SCALE / 1.2 + 1.0
CHAR_WIDTH = 0.5  # a character's advance, of a label's height: generous (digits and most letters are less)
TYPICAL_CANVAS_PX = 800.0  # the canvas height labels are laid out for before a browser reports its own
TEXT_CELLS_MIN = 0.35  # a label's height in cells when zoomed in (the layout's fixed offsets assume it)

Spot = tuple[float, float, float]  # (x, y, x where the text ends), in scene units


def text_cells(visible_height: float, canvas_px: float = TYPICAL_CANVAS_PX) -> float:
    """A label's height in grid cells when a canvas ``canvas_px`` tall shows ``visible_height`` cells: a
    label keeps its size on screen, so zoomed out over a large run it is several cells tall."""
    return max(TEXT_CELLS_MIN, LABEL_TEXT_PX * visible_height / canvas_px)


def label_width(text: str, height: float) -> float:
    """A label's width in cells, padding included, for a label ``height`` cells tall."""
    return CHAR_WIDTH * height * len(text) + 0.2 * height


def label_box(text: str, spot: Spot, height: float) -> Bounds:
    """The rectangle (x0, y0, x1, y1) a label covers, drawn from ``spot`` (its lower left, as viser's
    bottom-left anchor places it)."""
    x, y, x_end = spot
    return (x, y, max(x_end, x + label_width(text, height)), y + height)


def _overlap_area(a: Bounds, b: Bounds) -> float:
    """The area two boxes share (a sliver of a cell counts: two labels laid out touching read as one)."""
    return max(0.0, min(a[2], b[2]) - max(a[0], b[0])) * max(0.0, min(a[3], b[3]) - max(a[1], b[1]))


def _overlaps(a: Bounds, b: Bounds) -> bool:
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


def free_label_spot(
    spots: list[Spot],
    robots: np.ndarray,
    text: str = "",
    height: float = TEXT_CELLS_MIN,
    taken: list[Bounds] | None = None,
) -> tuple[float, float, float]:
    """The first of ``spots`` where the text covers no robot, no robot's number (upper right of its
    disc) and no label already placed (``taken``: their :func:`label_box`); else the first that covers
    no label (a label over a robot still reads, two labels over each other do not); else the one that
    covers the least of other labels."""
    taken = taken or []
    clear_of_labels = []
    least: tuple[float, Spot] | None = None
    for spot in spots:
        box = label_box(text, spot, height)
        covered_labels = sum(_overlap_area(box, t) for t in taken)
        if least is None or covered_labels < least[0]:
            least = (covered_labels, spot)
        if covered_labels > 0:
            continue
        clear_of_labels.append(spot)
        covered = (
            (robots[:, 1] - 0.4 < box[3])
            & (robots[:, 1] + 0.7 > box[1])
            & (robots[:, 0] - 0.5 < box[2])
            & (robots[:, 0] + 0.7 > box[0])
        )
        if not covered.any():
            return (spot[0], spot[1], 0.1)
    x, y, _ = clear_of_labels[0] if clear_of_labels else (least[1] if least is not None else spots[0])
    return (x, y, 0.1)


def cells_label_at(
    cells: np.ndarray,
    robots: np.ndarray,
    text: str = "",
    height: float = TEXT_CELLS_MIN,
    taken: list[Bounds] | None = None,
) -> tuple[float, float, float]:
    """Where a set of cells' label goes: just above their top row; when a robot stands where the text
    would be (a pattern drawn among the robots, as the Unsolvable box demo's is), just below their bottom
    row, else to the right of their top row (then a row higher, to their left, a row lower). So the
    label does not cover a robot, nor another label (``taken``) where a place is free of them."""
    left, right = float(cells[:, 0].min()) - 0.4, float(cells[:, 0].max())
    top, bottom = float(cells[:, 1].max()), float(cells[:, 1].min())
    below = bottom - 0.55 - height  # its text ends just under the bottom row, however tall it is
    return free_label_spot(
        [
            (left, top + 0.6, right + 0.5),
            (left, below, right + 0.5),
            (right + 0.7, top, right + 3.7),
            (left, top + 0.8 + height, right + 0.5),
            (left - 0.3 - label_width(text, height), top, left - 0.3),
            (left, below - height - 0.2, right + 0.5),
        ],
        robots,
        text,
        height,
        taken,
    )


def frame_label_at(
    origin: tuple[float, float],
    y_sign: int,
    robots: np.ndarray,
    text: str = "",
    height: float = TEXT_CELLS_MIN,
    taken: list[Bounds] | None = None,
) -> tuple[float, float, float]:
    """Where a frame's label goes: under its origin (on the side away from its +y arm), else beyond the
    end of its x arm, else past the tip of its y arm; not over a robot or its number where one of these
    is free (the leader's neighbours crowd its row), never over another label (``taken``) where one is
    free of labels, and under the origin when none is."""
    ox, oy = origin
    away = oy + 0.5 if y_sign < 0 else oy - 0.45 - height
    tip = oy + 2.6 if y_sign > 0 else oy - 2.25 - height
    under, beyond_x = (ox, away, ox + 3.0), (ox + 2.4, oy, ox + 5.4)
    lower = away - height - 0.3 if y_sign > 0 else away + height + 0.3  # past a robot's label under it
    left = ox - 0.6 - label_width(text, height)
    spots = [under, beyond_x, (ox - 0.4, tip, ox + 2.6), (ox, lower, ox + 3.0), (left, oy - 0.25, ox - 0.6)]
    # Farther out, for a crowded corner (Compare's small runs): past the numbers over the y arm's tip,
    # and a row below the lower place.
    above_tip = tip + 1.2 * height + 0.3 if y_sign > 0 else tip - 1.2 * height - 0.3
    lowest = lower + (-1 if y_sign > 0 else 1) * (height + 0.3)
    spots += [(ox - 0.4, above_tip, ox + 2.6), (ox, lowest, ox + 3.0)]
    return free_label_spot(spots, robots, text, height, taken)


def line_label_at(
    end: tuple[float, float],
    robots: np.ndarray,
    text: str = "",
    height: float = TEXT_CELLS_MIN,
    taken: list[Bounds] | None = None,
) -> tuple[float, float, float]:
    """Where a line's label goes: just past its end (a horizontal line's right end, a vertical one's
    top), else beside the end above or below the line; over no label where one of these is free."""
    x, y = end
    width = label_width(text, height)
    spots = [(x + 0.2, y - height / 2, x + 0.2), (x - width, y + 0.2, x), (x - width, y - 0.2 - height, x),
             (x + 0.2, y + 0.2, x + 0.2), (x + 0.2, y - 0.2 - height, x + 0.2)]  # fmt: skip
    return free_label_spot(spots, robots, text, height, taken)
