"""Images the visualiser exports: browser renders flattened onto white, as a PNG or an animated GIF."""

from __future__ import annotations

from collections.abc import Sequence

import imageio.v3 as iio
import numpy as np


def on_white(image: np.ndarray) -> np.ndarray:
    """An (H, W, 3) uint8 image: an (H, W, 4) render with its transparent background made white.

    viser's canvas is transparent (the page's background shows through it), so a render read back from
    the browser is transparent wherever nothing was drawn; a saved image should look like the page.
    An (H, W, 3) image is returned as it is."""
    image = np.asarray(image)
    if image.ndim != 3 or image.shape[2] not in (3, 4):
        raise ValueError(f"expected an (H, W, 3) or (H, W, 4) image, got shape {image.shape}")
    if image.shape[2] == 3:
        return image.astype(np.uint8)
    alpha = image[:, :, 3:4].astype(np.float32) / 255.0
    rgb = image[:, :, :3].astype(np.float32) * alpha + 255.0 * (1.0 - alpha)
    return np.clip(np.rint(rgb), 0, 255).astype(np.uint8)


def shrink(image: np.ndarray, factor: int) -> np.ndarray:
    """``image`` ``factor`` times smaller each way, each pixel the mean of a factor × factor block
    (edge rows and columns that do not fill a block are dropped)."""
    if factor <= 1:
        return image
    h, w = image.shape[0] // factor * factor, image.shape[1] // factor * factor
    blocks = image[:h, :w].reshape(h // factor, factor, w // factor, factor, -1).astype(np.float32)
    return np.rint(blocks.mean(axis=(1, 3))).astype(np.uint8)


def png_on_white(image: np.ndarray) -> bytes:
    """PNG bytes of a render, its transparent background made white (:func:`on_white`)."""
    return iio.imwrite("<bytes>", on_white(image), extension=".png")


def gif_on_white(frames: Sequence[np.ndarray], seconds: float | Sequence[float]) -> bytes:
    """An animated GIF, looping, of renders of one size, each shown ``seconds`` (one for all, or one per
    frame; GIF keeps hundredths of a second)."""
    if not frames:
        raise ValueError("no frames to encode")
    each = [seconds] * len(frames) if isinstance(seconds, int | float) else list(seconds)
    if len(each) != len(frames):
        raise ValueError(f"{len(each)} durations for {len(frames)} frames")
    flat = np.stack([on_white(f) for f in frames])
    return iio.imwrite("<bytes>", flat, extension=".gif", duration=[round(1000 * s) for s in each], loop=0)
