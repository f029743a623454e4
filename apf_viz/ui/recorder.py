"""Recording what one browser shows, as an animated GIF: the "Record GIF" button.

A thread asks the browser for a render up to ``RECORD_FPS`` times a second (viser's ``get_render``: the
browser draws the scene once more and sends it back) until it is stopped, ``MAX_SECONDS`` have passed or
the browser goes away. The engine and the render loop never wait for it. Frames are rendered at the
canvas's own size and shrunk here: a render at another size would draw point sprites out of scale. The
GIF plays at the rate the frames were actually taken (a software-rendered browser is slower than
``RECORD_FPS``), so it runs in real time.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from typing import Literal

import numpy as np

from apf_viz.ui.image import gif_on_white, shrink

RECORD_FPS = 4.0
MAX_SECONDS = 30.0  # a recording stops by itself after this long: under 100 MB of frames at GIF_WIDTH
GIF_WIDTH = 640  # at most; the canvas is shrunk by a whole factor
RENDER_TIMEOUT = 15.0  # seconds a software-rendered browser gets for one frame


def canvas_size(client) -> tuple[int, int]:
    """(height, width) of a browser's canvas, in the pixels ``get_render`` takes."""
    try:
        return max(16, int(client.camera.image_height)), max(16, int(client.camera.image_width))
    except AssertionError:  # the browser has not reported its canvas yet
        return 720, 1280


def render_view(
    client, transport_format: Literal["png", "jpeg"], size: tuple[int, int] | None = None
) -> np.ndarray:
    """What ``client`` shows now, ``size`` (height, width) pixels, by default its canvas's own size (a
    render at another size draws point sprites out of scale). Raises viser's ``TimeoutError`` or
    ``RuntimeError`` when the browser returns no frame."""
    height, width = size or canvas_size(client)
    return client.get_render(height, width, transport_format=transport_format, timeout=RENDER_TIMEOUT)


class GifRecorder:
    """Frames of one client's view. When recording ends, ``done`` gets the GIF (None if no frame was
    taken) and why it ended early ("" when stopped or out of time)."""

    def __init__(self, client, done: Callable[[bytes | None, str], None]) -> None:
        self.client = client
        self.frames: list[np.ndarray] = []
        self._done = done
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="apf-viz-gif", daemon=True)
        self._thread.start()

    def stop(self) -> None:
        """Stop recording; the GIF is delivered from the recording thread."""
        self._stop.set()

    def _run(self) -> None:
        reason = ""
        size = canvas_size(self.client)  # fixed for the recording: a GIF's frames share one size
        factor = -(-size[1] // GIF_WIDTH)
        started = time.perf_counter()
        while not self._stop.is_set() and time.perf_counter() - started < MAX_SECONDS:
            t0 = time.perf_counter()
            try:
                # JPEG: a smaller payload, already on white; the GIF's palette is lossy anyway
                self.frames.append(shrink(render_view(self.client, "jpeg", size), factor))
            except (TimeoutError, RuntimeError) as err:  # viser's errors for no frame / a lost browser
                reason = str(err)
                break
            self._stop.wait(max(0.0, 1.0 / RECORD_FPS - (time.perf_counter() - t0)))
        if not self.frames:
            self._done(None, reason or "no frame was recorded")
            return
        taken = len(self.frames) / max(time.perf_counter() - started, 1e-3)
        self._done(gif_on_white(self.frames, min(RECORD_FPS, taken)), reason)
