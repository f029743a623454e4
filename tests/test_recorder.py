"""The GIF recorder with a stand-in browser: when it stops, what it hands over, and why."""

from __future__ import annotations

import threading
import time
from io import BytesIO
from types import SimpleNamespace

import imageio.v3 as iio
import numpy as np
from PIL import Image, ImageSequence

import apf_viz.ui.recorder as recorder
from apf_viz.ui.recorder import GifRecorder, canvas_size, frame_durations


class FakeBrowser:
    """Answers get_render with frames of rising grey, or fails from frame ``fail_at`` on."""

    def __init__(self, fail_at: int | None = None, width: int = 1300, height: int = 400) -> None:
        self.camera = SimpleNamespace(image_width=width, image_height=height)
        self.asked: list[tuple[int, int]] = []
        self.fail_at = fail_at

    def get_render(self, height, width, *, transport_format, timeout):
        self.asked.append((height, width))
        if self.fail_at is not None and len(self.asked) > self.fail_at:
            raise RuntimeError("Render request failed: the client disconnected before returning a frame.")
        grey = (37 * len(self.asked)) % 256  # distinct greys: the GIF merges no two frames
        return np.full((height, width, 3), grey, dtype=np.uint8)


def record(browser, frames: int | None = None, keep: list | None = None) -> tuple[bytes | None, str]:
    """Record until ``frames`` frames are taken (then stop), or until the recorder ends by itself.
    Paced by frames, never by the clock: a loaded machine only makes it slower."""
    got: list[tuple[bytes | None, str]] = []
    finished = threading.Event()
    rec = GifRecorder(browser, lambda gif, why: (got.append((gif, why)), finished.set()))
    if keep is not None:
        keep.append(rec)
    if frames is not None:
        while len(rec.frames) < frames and not finished.is_set():
            time.sleep(0.01)
        rec.stop()
    assert finished.wait(120), "the recorder never finished"
    return got[0]


class SlowBrowser(FakeBrowser):
    """A browser on a loaded machine: each render takes a different, long time."""

    def __init__(self, delays: list[float]) -> None:
        super().__init__()
        self.delays = delays

    def get_render(self, height, width, *, transport_format, timeout):
        time.sleep(self.delays[len(self.asked) % len(self.delays)])
        return super().get_render(height, width, transport_format=transport_format, timeout=timeout)


def gif_durations(gif: bytes) -> list[float]:
    with Image.open(BytesIO(gif)) as image:
        return [frame.info["duration"] / 1000 for frame in ImageSequence.Iterator(image)]


def test_frame_durations_run_until_the_next_frame_and_the_last_until_the_end():
    assert frame_durations([1.0, 1.25, 2.0], 2.5) == [0.25, 0.75, 0.5]
    assert frame_durations([3.0], 3.25) == [0.25]


def test_the_gif_lasts_as_long_as_the_recording_on_its_own_clock_however_slow_the_browser():
    """Whatever the load, each frame shows from when it was asked for until the next was, never shorter
    than a frame at RECORD_FPS, and the whole GIF as long as the recording (the recorder's clock)."""
    keep: list[GifRecorder] = []
    gif, why = record(SlowBrowser([0.0, 0.4, 0.05, 0.7]), frames=6, keep=keep)
    rec = keep[0]
    assert gif is not None and why == ""
    durations = gif_durations(gif)
    expected = frame_durations(rec.taken, rec.ended)
    assert len(rec.taken) >= 6 and len(durations) == len(expected)  # frames differ: none are merged
    assert all(abs(d - e) < 0.011 for d, e in zip(durations, expected, strict=True))  # GIF: 10 ms steps
    assert min(expected) >= 1 / recorder.RECORD_FPS - 1e-6
    assert abs(sum(durations) - (rec.ended - rec.taken[0])) < 0.011 * len(durations)


def test_stopping_hands_over_a_gif_of_the_frames_shrunk_to_gif_width(monkeypatch):
    monkeypatch.setattr(recorder, "RECORD_FPS", 20.0)
    browser = FakeBrowser()
    gif, why = record(browser, frames=3)
    assert why == "" and gif is not None
    frames = iio.imread(gif, extension=".gif", index=None)
    assert set(browser.asked) == {(400, 1300)}  # rendered at the canvas's own size ...
    assert frames.shape[1:] == (400 // 3, 1300 // 3, 3)  # ... and shrunk by a whole factor to ≤ GIF_WIDTH
    assert 2 <= len(frames) <= len(browser.asked)


def test_a_recording_ends_by_itself_after_max_seconds(monkeypatch):
    monkeypatch.setattr(recorder, "RECORD_FPS", 20.0)
    monkeypatch.setattr(recorder, "MAX_SECONDS", 0.25)
    gif, why = record(FakeBrowser())  # never stopped
    assert gif is not None and why == ""


def test_a_browser_that_goes_away_ends_the_recording_with_its_reason():
    gif, why = record(FakeBrowser(fail_at=2))
    assert gif is not None and len(iio.imread(gif, extension=".gif", index=None)) == 2
    assert "disconnected" in why
    gif, why = record(FakeBrowser(fail_at=0))
    assert gif is None and "disconnected" in why


def test_canvas_size_falls_back_before_the_browser_reports_its_canvas():
    class Unreported:
        @property
        def image_width(self):
            raise AssertionError

        image_height = image_width

    assert canvas_size(SimpleNamespace(camera=Unreported())) == (720, 1280)
    assert canvas_size(FakeBrowser(width=800, height=600)) == (600, 800)
