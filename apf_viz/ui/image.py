"""Images the visualiser exports: a browser's render, flattened and encoded as PNG."""

from __future__ import annotations

import imageio.v3 as iio
import numpy as np


def png_on_white(rgba: np.ndarray) -> bytes:
    """PNG bytes of an (H, W, 4) render with its transparent background made white.

    viser's canvas is transparent (the page's background shows through it), so a render read back from
    the browser is transparent wherever nothing was drawn; a saved screenshot should look like the page.
    An (H, W, 3) image is encoded as it is."""
    image = np.asarray(rgba)
    if image.ndim != 3 or image.shape[2] not in (3, 4):
        raise ValueError(f"expected an (H, W, 3) or (H, W, 4) image, got shape {image.shape}")
    if image.shape[2] == 4:
        alpha = image[:, :, 3:4].astype(np.float32) / 255.0
        rgb = image[:, :, :3].astype(np.float32) * alpha + 255.0 * (1.0 - alpha)
        image = np.clip(np.rint(rgb), 0, 255).astype(np.uint8)
    return iio.imwrite("<bytes>", image.astype(np.uint8), extension=".png")
