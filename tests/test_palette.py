"""The colours of a failure picture stay apart for every viewer (issue #23, item 6).

Colour differences are CIELAB ΔE (CIE76) after simulating protan-, deutan- and tritanopia with Machado,
Oliveira & Fernandes' (2009) matrices at full severity; about 2.3 is just noticeable, and a difference of
25 is told apart at a glance."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from apf_viz.algorithms.apf_opaque_grid.portrayal import K_COLOR, LEGEND
from apf_viz.workbench.palette import MARK_COLORS, MARK_SHAPES

VISION = {
    "normal": np.eye(3),
    "protan": np.array(
        [[0.152286, 1.052583, -0.204868], [0.114503, 0.786281, 0.099216], [-0.003882, -0.048116, 1.051998]]
    ),
    "deutan": np.array(
        [[0.367322, 0.860646, -0.227968], [0.280085, 0.672501, 0.047413], [-0.011820, 0.042940, 0.968881]]
    ),
    "tritan": np.array(
        [[1.255528, -0.076749, -0.178779], [-0.078411, 0.930809, 0.147602], [0.004733, 0.691367, 0.303900]]
    ),
}


def _linear(rgb) -> np.ndarray:
    c = np.asarray(rgb, dtype=float) / 255.0
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def _lab(linear: np.ndarray) -> np.ndarray:
    xyz = np.array([[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]]) @ linear
    t = xyz / np.array([0.95047, 1.0, 1.08883])
    f = np.where(t > (6 / 29) ** 3, np.cbrt(t), t / (3 * (6 / 29) ** 2) + 4 / 29)
    return np.array([116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])])


def seen_difference(a, b, vision: str) -> float:
    """ΔE between two sRGB colours as a viewer with ``vision`` sees them."""
    m = VISION[vision]
    return float(np.linalg.norm(_lab(np.clip(m @ _linear(a), 0, 1)) - _lab(np.clip(m @ _linear(b), 0, 1))))


def _closest(colors: dict[str, tuple[int, int, int]], vision: str) -> tuple[float, str, str]:
    return min(
        (seen_difference(a, b, vision), x, y) for (x, a), (y, b) in itertools.combinations(colors.items(), 2)
    )


def test_the_difference_measure_fails_the_old_leader_and_collision_reds():
    # The colours the issue reported: leader (220,30,30) against collision (230,0,0).
    assert all(seen_difference((220, 30, 30), (230, 0, 0), v) < 15 for v in VISION)


@pytest.mark.parametrize("vision", VISION)
def test_leader_collision_selection_and_never_acts_are_apart_at_a_glance(vision):
    marks = {
        "leader": LEGEND["leader"].color,
        "collision": MARK_COLORS["collision"],
        "selected": MARK_COLORS["selected"],
        "never": MARK_COLORS["never"],
    }
    gap, a, b = _closest(marks, vision)
    assert gap >= 25, f"{a} and {b}: ΔE {gap:.1f} for {vision} vision"


@pytest.mark.parametrize("vision", VISION)
def test_the_eight_lights_are_apart_for_every_viewer(vision):
    gap, a, b = _closest({light: style.color for light, style in LEGEND.items()}, vision)
    assert gap >= 15, f"{a} and {b}: ΔE {gap:.1f} for {vision} vision"


@pytest.mark.parametrize("vision", VISION)
def test_the_line_k_is_not_the_collision_colour(vision):
    assert seen_difference(K_COLOR, MARK_COLORS["collision"], vision) >= 25


def test_collision_selection_and_never_acts_differ_in_shape_too():
    shapes = [MARK_SHAPES[m] for m in ("collision", "selected", "never")]
    assert len(set(shapes)) == 3  # robots are discs: "selected" is a ring around one, the others are not


def test_every_light_disc_stands_out_from_the_white_grid_through_its_outline():
    # A pale light (off, leader1) shows on white because every disc sits on the dark outline.
    outline = MARK_COLORS["outline"]
    for light, style in LEGEND.items():
        assert seen_difference(style.color, outline, "normal") >= 25, light
