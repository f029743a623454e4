"""The GIF recorder with a stand-in browser: when it stops, what it hands over, and why."""

from __future__ import annotations

import threading
from types import SimpleNamespace

import imageio.v3 as iio
import numpy as np

import apf_viz.ui.recorder as recorder
from apf_viz.ui.recorder import GifRecorder, canvas_size


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
        return np.full((height, width, 3), min(255, 40 * len(self.asked)), dtype=np.uint8)


def record(browser, stop_after: float | None = None) -> tuple[bytes | None, str]:
    got: list[tuple[bytes | None, str]] = []
    finished = threading.Event()
    rec = GifRecorder(browser, lambda gif, why: (got.append((gif, why)), finished.set()))
    if stop_after is not None:
        finished.wait(stop_after)
        rec.stop()
    assert finished.wait(10), "the recorder never finished"
    return got[0]


def test_stopping_hands_over_a_gif_of_the_frames_shrunk_to_gif_width(monkeypatch):
    monkeypatch.setattr(recorder, "RECORD_FPS", 20.0)
    browser = FakeBrowser()
    gif, why = record(browser, stop_after=0.3)
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
