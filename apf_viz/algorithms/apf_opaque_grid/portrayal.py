"""How the paper's algorithm describes itself to the screen (:mod:`apf_viz.core.portrayal`): its eight
lights, the line K, the leader's frame, where the pattern will form, and the stage.

Overlays are computed from the global configuration for display only; no robot ever sees them.
"""

from __future__ import annotations

from apf_viz.algorithms.apf_opaque_grid.pattern_formation import embedded_targets
from apf_viz.core.grid import Point
from apf_viz.core.portrayal import Cells, Configuration, Frame, LightStyle, Line, Mark, Overlays

LEGEND: dict[str, LightStyle] = {
    "off": LightStyle((150, 150, 150), "no role yet (every robot starts off)"),
    "terminal1": LightStyle((50, 110, 255), "Phase 1: a terminal robot of the leftmost line L_1"),
    "symmetric": LightStyle((160, 80, 220), "Phase 1: L_1's terminal pair, R_I symmetric about K"),
    "decider": LightStyle((0, 190, 200), "Phase 2: one of the two robots that decide the leader"),
    "call": LightStyle((255, 150, 0), "Phase 2: answers the deciders (R_I symmetric, closest to K)"),
    "leader1": LightStyle((255, 80, 170), "Phase 2: elected, walking to a corner to become leader"),
    "leader": LightStyle((220, 30, 30), "Phase 3: the leader r₀; its position fixes the frame"),
    "done": LightStyle((40, 170, 60), "Phase 3: on its target"),
}

K_COLOR = (200, 0, 200)

STAGES = {
    1: "Phase 1: leader election (Algorithm 1)",
    2: "Phase 2: leader selection (Algorithm 2)",
    3: "Phase 3: pattern formation (Algorithm 3)",
    4: "Formed: every robot is done",
}


def stage(lights: tuple[str, ...]) -> str:
    """The stage the lights show (the robots themselves dispatch on what each sees, docs/ALGORITHM.md)."""
    present = set(lights)
    if present == {"done"}:
        return STAGES[4]
    if present & {"leader", "done"}:
        return STAGES[3]
    if present & {"decider", "call", "leader1"}:
        return STAGES[2]
    return STAGES[1]


def line_K(positions: tuple[Point, ...], lights: tuple[str, ...]) -> float | None:
    """K: the midline of two deciders, or of two terminal1 robots, on one vertical line."""
    for light in ("decider", "terminal1"):
        by_x: dict[int, list[int]] = {}
        for (x, y), lt in zip(positions, lights, strict=True):
            if lt == light:
                by_x.setdefault(x, []).append(y)
        for ys in by_x.values():
            if len(ys) == 2:
                return (ys[0] + ys[1]) / 2
    return None


def leader_frame(positions: tuple[Point, ...], lights: tuple[str, ...]) -> tuple[Point, int] | None:
    """The leader's frame in global terms: its origin (the leader + (0, s)) and s, the side of the
    others (the followers' reading of it, :func:`~.pattern_formation.follower_frame`)."""
    if "leader" not in lights:
        return None
    lx, ly = positions[lights.index("leader")]
    others = [y for (x, y), lt in zip(positions, lights, strict=True) if lt != "leader" and y != ly]
    s = 1 if not others or others[0] > ly else -1
    return (lx, ly + s), s


def placed_frame(
    positions: tuple[Point, ...], lights: tuple[str, ...], targets: tuple[Point, ...]
) -> tuple[Point, int] | None:
    """The frame the placed robots fix once every robot but the leader is done: the leader then walks
    to t_{n−1}, and a frame read off its position would walk with it. As the leader reads it (LA,
    :func:`~.pattern_formation._anchored_frame`): +y towards the done robots off its row, t_{n−2} the
    leftmost robot of the lowest done row. None before that moment."""
    if "leader" not in lights or len(targets) < 2:
        return None
    others = [lt for lt in lights if lt != "leader"]
    if not others or any(lt != "done" for lt in others):
        return None
    ly = positions[lights.index("leader")][1]
    done = [p for p, lt in zip(positions, lights, strict=True) if lt == "done"]
    off_row = [y for _, y in done if y != ly]
    s = (1 if off_row[0] > ly else -1) if off_row else 1
    lowest = min(s * (y - ly) for _, y in done)
    bx, by = min((p for p in done if s * (p[1] - ly) == lowest), key=lambda p: p[0])
    tx, ty = targets[-2]
    return (bx - tx, by - s * ty), s


def overlays(config: Configuration) -> Overlays:
    marks: list[Mark] = []
    k = line_K(config.positions, config.lights)
    if k is not None:
        marks.append(Line("y", k, "K", K_COLOR))
    targets = embedded_targets(tuple(config.pattern))
    frame = placed_frame(config.positions, config.lights, targets) or leader_frame(
        config.positions, config.lights
    )
    if frame is not None:
        (ox, oy), s = frame
        marks.append(Frame((ox, oy), s, "the leader's frame"))
        marks.append(Cells(tuple((ox + x, oy + s * y) for x, y in targets), "targets", "placed"))
    elif set(config.lights) == {"done"}:
        marks.append(Cells(config.positions, "targets", "placed"))  # formed: the pattern is where they are
    else:
        x0 = max(p[0] for p in config.start) + 3
        y0 = min(p[1] for p in config.start) - 1
        preview = tuple((x0 + x, y0 + y) for x, y in targets)
        marks.append(Cells(preview, "pattern, not yet placed", "preview"))
    return Overlays(tuple(marks), stage(config.lights))
