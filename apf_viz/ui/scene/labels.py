"""Where text goes on the canvas: a label keeps its size on screen, so it is laid out in cells for
the framed zoom, clear of robots, their numbers and other labels."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from apf_viz.ui.scene.style import STALE_MARK, Bounds


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


def spread(
    labels: list[tuple[str, tuple[float, float, float]]],
    pts: list[list[float]],
    height: float,
    left_edge: float = -float("inf"),
    taken: Sequence[Bounds] = (),
) -> list[tuple[str, tuple[float, float, float]]]:
    """Robots' labels (:func:`number_labels`, at each robot's upper right) moved where they cover no
    other label and no other robot when their own place does (robots a cell apart, zoomed out: Compare's
    two runs side by side): below right, left, below left, above or further below their robot, in that
    order; the plain numbers first, and where they always are, so that a long label gives way to them.
    ``height``: a label's height in cells; ``left_edge``: how far left a framed camera shows (a label
    moved past it would not be seen: better over a neighbour). Where no place is free, the one that
    covers least. ``taken``: labels already on the canvas (another run's), kept clear of as well."""
    discs = [(x - 0.4, y - 0.4, x + 0.4, y + 0.4) for x, y in pts]
    order = sorted(range(len(labels)), key=lambda i: not labels[i][0].isdigit())  # plain numbers first
    taken = list(taken)
    placed: dict[int, tuple[float, float, float]] = {}
    for i in order:
        text, (x0, y0, z) = labels[i]
        x, y = x0 - 0.25, y0 - 0.3  # the robot it belongs to
        width = 0.55 * height * len(text)
        spots = [(x + 0.25, y + 0.3), (x + 0.25, y - 0.55 - height), (x - 0.35 - width, y + 0.3),
                 (x - 0.35 - width, y - 0.55 - height), (x + 0.25, y + 0.3 + height + 0.2),
                 (x + 0.25, y - 0.75 - 2 * height)]  # fmt: skip
        chosen = spots[0]
        others = [d for d in discs if not (d[0] < x < d[2] and d[1] < y < d[3])]  # not its own robot
        least = float("inf")
        for sx, sy in () if text.isdigit() else spots:  # a plain number keeps its place: it is read there
            box = label_box(text, (sx, sy, sx), height)
            if box[0] < left_edge:
                continue
            # Another label covered is worse than a robot: two texts over each other read as neither.
            cost = 4 * sum(_overlap_area(box, t) for t in taken) + sum(_overlap_area(box, d) for d in others)
            if cost < least:
                least, chosen = cost, (sx, sy)
            if cost == 0:
                break
        taken.append(label_box(text, (chosen[0], chosen[1], chosen[0]), height))
        placed[i] = (chosen[0], chosen[1], z)
    return [(labels[i][0], placed[i]) for i in range(len(labels))]


LABEL_TEXT_PX = 15.0  # a label's height on screen, padding included (viser's labels keep a screen size)
TYPICAL_CANVAS_PX = 800.0  # the canvas height labels are laid out for (1400×900 and 1024×768 windows)
TEXT_CELLS_MIN = 0.35  # a label's height in cells when zoomed in (the layout's fixed offsets assume it)

Spot = tuple[float, float, float]  # (x, y, x where the text ends), in scene units


def text_cells(visible_height: float) -> float:
    """A label's height in grid cells when the canvas shows ``visible_height`` cells: a label keeps its
    size on screen, so zoomed out over a large run it is several cells tall."""
    return max(TEXT_CELLS_MIN, LABEL_TEXT_PX * visible_height / TYPICAL_CANVAS_PX)


def label_box(text: str, spot: Spot, height: float) -> Bounds:
    """The rectangle (x0, y0, x1, y1) a label's text covers, drawn from ``spot`` (its lower left)."""
    x, y, x_end = spot
    return (x, y - 0.25, max(x_end, x + 0.55 * height * len(text)), y - 0.25 + max(0.5, height))


def _overlap_area(a: Bounds, b: Bounds) -> float:
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
            (left - 0.3 - 0.55 * height * len(text), top, left - 0.3),
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
    away = oy + 0.6 if y_sign < 0 else oy - 0.25 - height
    tip = oy + 2.6 if y_sign > 0 else oy - 2.25 - height
    under, beyond_x = (ox, away, ox + 3.0), (ox + 2.4, oy, ox + 5.4)
    lower = away - height - 0.3 if y_sign > 0 else away + height + 0.3  # past a robot's label under it
    left = ox - 0.6 - 0.55 * height * len(text)
    spots = [under, beyond_x, (ox - 0.4, tip, ox + 2.6), (ox, lower, ox + 3.0), (left, oy - 0.25, ox - 0.6)]
    return free_label_spot(spots, robots, text, height, taken)
