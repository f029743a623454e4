"""Exported screenshots: a transparent render is flattened onto white and encoded losslessly."""

from __future__ import annotations

import imageio.v3 as iio
import numpy as np
import pytest

from apf_viz.ui.image import png_on_white


def test_transparent_pixels_become_white_and_opaque_ones_keep_their_colour():
    rgba = np.zeros((2, 3, 4), dtype=np.uint8)
    rgba[0, 0] = (10, 200, 30, 255)  # opaque
    rgba[0, 1] = (0, 0, 0, 0)  # nothing drawn
    rgba[0, 2] = (0, 0, 0, 128)  # half-covered black: mid grey
    image = iio.imread(png_on_white(rgba), extension=".png")
    assert image.shape == (2, 3, 3)
    assert image[0, 0].tolist() == [10, 200, 30]
    assert image[0, 1].tolist() == [255, 255, 255]
    assert image[0, 2].tolist() == [127, 127, 127]


def test_an_rgb_image_is_encoded_unchanged_and_other_shapes_are_refused():
    rgb = np.arange(2 * 2 * 3, dtype=np.uint8).reshape(2, 2, 3)
    assert iio.imread(png_on_white(rgb), extension=".png").tolist() == rgb.tolist()
    with pytest.raises(ValueError, match=r"shape \(4, 4\)"):
        png_on_white(np.zeros((4, 4), dtype=np.uint8))
