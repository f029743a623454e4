"""A lecture hall for ``bench_ui.py --class N``: one real projector page (the presenter address, 1024×768)
and one real student page (the class address) in headless Chromium, and N lightweight class pages:
websocket clients that speak viser's protocol, send a camera as a page does (on connecting, then every
second), read every message the server sends, and have each selected a robot of its own.

The heart demo plays at 30 steps/s; for 10 s each page counts how often its ``Event`` number changes
(one change is one frame of the scene reaching it). Measured first with no lightweight pages, then with N.
"""

from __future__ import annotations

import asyncio
import threading
import time

import viser
import websockets
from playwright.sync_api import sync_playwright
from viser import _messages

from apf_viz.ui.app import App, demo_session, free_port

WINDOW_S = 10.0
SPEED = 30.0


def _camera() -> bytes:
    import msgspec

    message = _messages.ViewerCameraMessage(
        wxyz=(1.0, 0.0, 0.0, 0.0),
        position=(4.0, 0.0, 30.0),
        fov=0.9,
        near=0.01,
        far=1000.0,
        image_height=768,
        image_width=1024,
        look_at=(4.0, 0.0, 0.0),
        up_direction=(0.0, 0.0, 1.0),
    )
    return msgspec.msgpack.encode(message.as_serializable_dict())


class LightPages:
    """N websocket clients in one asyncio loop (a thread of its own): each sends its camera and reads."""

    def __init__(self, url: str, n: int) -> None:
        self.url, self.n = url, n
        self.received = [0] * n
        self._loop = asyncio.new_event_loop()
        self._stop: asyncio.Event | None = None
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._ready = threading.Event()

    def start(self) -> None:
        self._thread.start()
        self._ready.wait(60)

    def stop(self) -> None:
        if self._stop is not None:
            self._loop.call_soon_threadsafe(self._stop.set)
        self._thread.join(30)

    def _run(self) -> None:
        self._loop.run_until_complete(self._main())

    async def _main(self) -> None:
        self._stop = asyncio.Event()
        protocol = f"viser-v{viser.__version__}"
        sockets = []
        for _ in range(self.n):
            sockets.append(await websockets.connect(self.url, subprotocols=[protocol], max_size=None))
        self._ready.set()
        tasks = [asyncio.create_task(self._page(i, ws)) for i, ws in enumerate(sockets)]
        await self._stop.wait()
        for task in tasks:
            task.cancel()
        for ws in sockets:
            await ws.close()

    async def _page(self, i: int, ws) -> None:
        camera = _camera()

        async def read() -> None:
            async for message in ws:
                self.received[i] += len(message)

        reader = asyncio.create_task(read())
        try:
            while True:
                await ws.send(camera)
                await asyncio.sleep(1.0)
        finally:
            reader.cancel()


def _rate(page, start_record: str) -> float:
    return len(page.evaluate("window.__probe")[1]) / WINDOW_S


def _measure(app: App, projector, student, start_record: str) -> tuple[float, float, float]:
    session = app.session
    session.pause()
    session.reset()
    session.set_speed(SPEED)
    time.sleep(1.0)
    frames = app.frames
    session.toggle_play()
    time.sleep(0.5)
    projector.evaluate(start_record, [WINDOW_S * 1000])
    student.evaluate(start_record, [WINDOW_S * 1000])
    a, b = _rate(projector, start_record), _rate(student, start_record)
    sent = (app.frames - frames) / (WINDOW_S + 0.5)
    session.pause()
    return a, b, sent


def lecture_hall(n: int, args: list[str], start_record: str) -> None:
    app = App(demo_session(), port=free_port(), verbose=False)
    presenter_url, class_url = app.addresses
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=args)
        projector = browser.new_page(viewport={"width": 1024, "height": 768})
        projector.goto(presenter_url)
        projector.get_by_label("Event").wait_for(timeout=60_000)
        student = browser.new_page(viewport={"width": 1024, "height": 768})
        student.goto(class_url)
        student.get_by_label("Event").wait_for(timeout=60_000)
        time.sleep(2.0)
        alone = _measure(app, projector, student, start_record)
        print("| pages | projector updates/s | student page updates/s | server frames/s |")
        print("|---:|---:|---:|---:|")
        print(f"| 2 (no class) | {alone[0]:.1f} | {alone[1]:.1f} | {alone[2]:.1f} |", flush=True)
        pages = LightPages(class_url.replace("http://", "ws://").split("?")[0], n)
        pages.start()
        deadline = time.time() + 120
        while len(app.screens) < n + 2 and time.time() < deadline:
            time.sleep(0.2)
        robots = app.session.engine.current_points()
        light = [cid for cid, x in app.screens.items() if x.state.role == "class"][1:]
        for i, cid in enumerate(sorted(light)):
            app.session.click(robots[i % len(robots)], cid)  # each has selected a robot of its own
        app.request_render()
        time.sleep(2.0)
        full = _measure(app, projector, student, start_record)
        share = full[0] / alone[0] if alone[0] else float("nan")
        print(
            f"| 2 + {n} class pages (each a robot selected) | {full[0]:.1f} ({share:.2f} of alone) | "
            f"{full[1]:.1f} | {full[2]:.1f} |"
        )
        received = sum(pages.received) / max(1, n)
        print(f"({len(app.screens)} pages connected; each lightweight page read {received / 1e6:.1f} MB)")
        pages.stop()
        browser.close()
    app.stop()
