"""How the paper's algorithm describes itself to the screen (:mod:`apf_viz.core.portrayal`): its eight
lights, the line K, the leader's frame, where the pattern will form, and the stage.

Overlays are computed from the global configuration for display only; no robot ever sees them.
"""

from __future__ import annotations

from apf_viz.algorithms.apf_opaque_grid.pattern_formation import embedded_targets
from apf_viz.core.grid import Point
from apf_viz.core.portrayal import Cells, Configuration, Frame, LightStyle, Line, Mark, Overlays

LEGEND: dict[str, LightStyle] = {
    "off": LightStyle((195, 195, 195), "no role yet (every robot starts off)"),
    "terminal1": LightStyle((86, 180, 233), "Phase 1: a terminal robot of the leftmost line L_1"),
    "symmetric": LightStyle((0, 114, 178), "Phase 1: L_1's terminal pair, R_I symmetric about K"),
    "decider": LightStyle((204, 121, 167), "Phase 2: one of the two robots that decide the leader"),
    "call": LightStyle((230, 159, 0), "Phase 2: answers the deciders (R_I symmetric, closest to K)"),
    "leader1": LightStyle((240, 228, 66), "Phase 2: elected, walking to a corner to become leader"),
    # A square: the one robot that fixes the frame is found at a glance, and told from a done robot
    # ringed orange (computed) by its shape, not only its vermillion.
    "leader": LightStyle((213, 94, 0), "Phase 3: the leader r₀; its position fixes the frame", "square"),
    "done": LightStyle((0, 158, 115), "Phase 3: on its target"),
}

K_COLOR = (0, 130, 140)

STAGES = {
    1: "Phase 1: leader election (Algorithm 1)",
    2: "Phase 2: leader selection (Algorithm 2)",
    3: "Phase 3: pattern formation (Algorithm 3)",
    4: "Formed: every robot is done",
}


def stage(positions: tuple[Point, ...], lights: tuple[str, ...]) -> str:
    """The stage the configuration shows: the paper's phase, then the step within it that a lecture
    stops at (Next stage stops at every change). The robots themselves dispatch on what each sees
    (docs/ALGORITHM.md); this reading is for the screen only."""
    present = set(lights)
    if present == {"done"}:
        return STAGES[4]
    if present & {"leader", "done"}:
        return f"{STAGES[3]} — {_phase3_step(positions, lights)}"
    if "leader1" in present:
        return f"{STAGES[2]} — leader elected (leader1), walking to its corner"
    if "call" in present:
        return f"{STAGES[2]} — a robot closest to K answers with call"
    # A stage is named only when the configuration shows it: the second robot of a pair lights its
    # light a few events after the first (ASYNC), and the words must not run ahead of the screen. The
    # half-way stages share no words with the whole ones ("two deciders", "symmetric about K"): a
    # lecture's ``until: {"stage": …}`` matches words of a stage name and stops at the first match.
    if lights.count("decider") >= 2:
        return f"{STAGES[2]} — two deciders stand on L_1"
    if "decider" in present:
        return f"{STAGES[2]} — a robot lights decider; its partner has not yet"
    if lights.count("symmetric") >= 2:
        return f"{STAGES[1]} — L_1's terminal pair is symmetric about K"
    if "symmetric" in present:
        return f"{STAGES[1]} — one terminal robot lights symmetric; its partner has not yet"
    if "terminal1" in present:
        return f"{STAGES[1]} — L_1's terminal robots light terminal1"
    return f"{STAGES[1]} — every robot off"


def _phase3_step(positions: tuple[Point, ...], lights: tuple[str, ...]) -> str:
    """Lining up on the leader's row, then one stop per robot that reaches its target, then the
    leader's last walk (Algorithm 3)."""
    others = len(lights) - 1
    done = lights.count("done")
    if "leader" not in lights or done == others:
        return "the leader walks to the last target"
    if done:
        return f"{done} of {others} robots on their targets"
    lx, row = positions[lights.index("leader")]
    lined = {x for (x, y), lt in zip(positions, lights, strict=True) if y == row and lt != "leader"}
    if lined and lx + 1 not in lined:  # the line grows from the leader's side and leaves from it
        return "the line is complete; its left end leaves for the first target"
    return f"the leader at its corner; {len(lined)} of {others} robots lined up on its row"


def phase_of(stage: str) -> str:
    """The phase a stage belongs to (its text before the dash): the timeline labels phases only."""
    return stage.split(" — ")[0].split(":")[0]


def line_K(positions: tuple[Point, ...], lights: tuple[str, ...]) -> float | None:
    """K: the midline of two deciders, two symmetric or two terminal1 robots on one vertical line."""
    for light in ("decider", "symmetric", "terminal1"):
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
    return Overlays(tuple(marks), stage(config.positions, config.lights))
