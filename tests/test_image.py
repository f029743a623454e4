"""Exported screenshots: a transparent render is flattened onto white and encoded losslessly."""

from __future__ import annotations

from io import BytesIO

import imageio.v3 as iio
import numpy as np
import pytest
from PIL import Image, ImageSequence

from apf_viz.ui.image import gif_on_white, png_on_white, shrink


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


def test_shrink_averages_whole_blocks_and_drops_the_ragged_edge():
    image = np.zeros((5, 7, 3), dtype=np.uint8)
    image[0:2, 0:2] = (0, 100, 200)
    image[0, 0] = (40, 100, 200)
    small = shrink(image, 2)
    assert small.shape == (2, 3, 3)
    assert small[0, 0].tolist() == [10, 100, 200] and small[1, 2].tolist() == [0, 0, 0]
    assert shrink(image, 1) is image


def test_a_gif_loops_with_one_frame_per_render_each_for_its_own_time():
    frames = [np.full((6, 8, 4), (v, v, v, 255), dtype=np.uint8) for v in (0, 128, 255)]
    gif = gif_on_white(frames, 0.5)
    decoded = iio.imread(gif, extension=".gif", index=None)
    assert decoded.shape == (3, 6, 8, 3)
    assert [int(f[0, 0, 0]) for f in decoded] == [0, 128, 255]
    meta = iio.immeta(gif, extension=".gif")
    assert meta["duration"] == 500 and meta["loop"] == 0
    with Image.open(BytesIO(gif_on_white(frames, [0.25, 1.0, 0.3]))) as uneven:
        assert [f.info["duration"] for f in ImageSequence.Iterator(uneven)] == [250, 1000, 300]
    with pytest.raises(ValueError, match="no frames"):
        gif_on_white([], 0.25)
    with pytest.raises(ValueError, match="2 durations for 3 frames"):
        gif_on_white(frames, [0.25, 0.25])
