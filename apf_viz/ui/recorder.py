"""Recording what one browser shows, as an animated GIF: the "Record GIF" button.

A thread asks the browser for a render up to ``RECORD_FPS`` times a second (viser's ``get_render``: the
browser draws the scene once more and sends it back) until it is stopped, ``MAX_SECONDS`` have passed or
the browser goes away. The engine and the render loop never wait for it. Frames are rendered at the
canvas's own size and shrunk here: a render at another size would draw point sprites out of scale. The
GIF shows each frame until the next was asked for (a software-rendered browser is slower than
``RECORD_FPS``), so it runs in real time on the recorder's own clock.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Sequence
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


def frame_durations(taken: Sequence[float], ended: float) -> list[float]:
    """How long each frame shows, in seconds: until the next frame was asked for, the last one until the
    recording ended. The GIF then lasts exactly as long as the recording, on the recorder's own clock,
    however slowly a loaded machine rendered."""
    return [b - a for a, b in zip(taken, [*taken[1:], ended], strict=True)]


class GifRecorder:
    """Frames of one client's view. When recording ends, ``done`` gets the GIF (None if no frame was
    taken) and why it ended early ("" when stopped or out of time).

    ``taken`` holds when each frame was asked for and ``ended`` when the recording stopped (both
    ``time.perf_counter``); frames are asked for at least ``1 / RECORD_FPS`` apart, so none shows shorter."""

    def __init__(self, client, done: Callable[[bytes | None, str], None]) -> None:
        self.client = client
        self.frames: list[np.ndarray] = []
        self.taken: list[float] = []
        self.ended: float | None = None
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
        clock = time.perf_counter
        started = clock()
        while not self._stop.is_set() and clock() - started < MAX_SECONDS:
            asked = clock()
            try:
                # JPEG: a smaller payload, already on white; the GIF's palette is lossy anyway
                frame = shrink(render_view(self.client, "jpeg", size), factor)
            except (TimeoutError, RuntimeError) as err:  # viser's errors for no frame / a lost browser
                reason = str(err)
                break
            self.frames.append(frame)
            self.taken.append(asked)
            while not self._stop.is_set() and clock() < asked + 1.0 / RECORD_FPS:
                self._stop.wait(asked + 1.0 / RECORD_FPS - clock())
        self.ended = max(clock(), self.taken[-1] + 1.0 / RECORD_FPS) if self.taken else clock()
        if not self.frames:
            self._done(None, reason or "no frame was recorded")
            return
        self._done(gif_on_white(self.frames, frame_durations(self.taken, self.ended)), reason)
