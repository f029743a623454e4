"""Local frames: every robot agrees on +x; its y-axis may be flipped by the adversary (paper §2, *Robots*).

A frame is one bit, ``y_up``: True when the robot's +y is the global +y. Offsets and moves cross between
the global frame (engine, files, scene) and a robot's local frame only through these functions.
"""

from __future__ import annotations

import random
from typing import overload

from apf_viz.core.grid import Direction, Point


def to_local(offset: Point, y_up: bool) -> Point:
    """A global offset seen in the robot's own frame."""
    return (offset[0], offset[1] if y_up else -offset[1])


@overload
def move_to_global(move: Direction, y_up: bool) -> Direction:
    """A move: its global direction."""
    ...


@overload
def move_to_global(move: None, y_up: bool) -> None:
    """Staying: None."""
    ...


@overload
def move_to_global(move: Direction | None, y_up: bool) -> Direction | None:
    """A move or None: the global direction, or None."""
    ...


def move_to_global(move: Direction | None, y_up: bool) -> Direction | None:
    """The global direction of a move the robot computed in its own frame (None = stay)."""
    if move is None or y_up or move in (Direction.LEFT, Direction.RIGHT):
        return move
    return Direction.DOWN if move is Direction.UP else Direction.UP


# A flip is an involution, so the same map takes a global move back to the local frame.
move_to_local = move_to_global


def random_y_up(k: int, seed: int) -> list[bool]:
    """The adversary's flips when a start file gives none: random, but a function of the seed."""
    rng = random.Random(f"y_up:{seed}")
    return [rng.random() < 0.5 for _ in range(k)]
