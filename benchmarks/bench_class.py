"""A lecture hall for ``bench_ui.py --class N``: one real projector page (the presenter address, 1024×768)
and one real student page (the class address) in headless Chromium, and N lightweight class pages:
websocket clients that speak viser's protocol, send a camera as a page does (on connecting, then every
second), read every message the server sends, and have each selected a robot of its own.

The heart demo plays at 30 steps/s; for 10 s each page counts how often its ``Event`` number changes
(one change is one frame of the scene reaching it). Measured first with no lightweight pages, then with N.
"""

from __future__ import annotations

import asyncio
import contextlib
import multiprocessing
import statistics
import time

import viser
import websockets
from playwright.sync_api import sync_playwright
from viser import _messages
from websockets.typing import Subprotocol

from apf_viz.ui.app import App, demo_session, free_port
from apf_viz.workbench.classroom import OWN_SPEED

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
    """N websocket clients in one asyncio loop, in a process of their own (as a class's laptops are
    machines of their own: their reading must not take the server's interpreter): each sends its camera
    and reads every message."""

    def __init__(self, url: str, n: int) -> None:
        self.url, self.n = url, n
        self._ready = multiprocessing.Event()
        self._stop = multiprocessing.Event()
        self._received = multiprocessing.Value("d", 0.0)
        self._cpu = multiprocessing.Value("d", 0.0)  # the process's CPU seconds, from connected to stopped
        self._process = multiprocessing.Process(
            target=_pages, args=(url, n, self._ready, self._stop, self._received, self._cpu), daemon=True
        )

    def start(self) -> None:
        self._process.start()
        self._ready.wait(60)

    def stop(self) -> None:
        self._stop.set()
        self._process.join(30)

    @property
    def received(self) -> float:
        """Bytes read, in all."""
        return self._received.value

    @property
    def cpu(self) -> float:
        """CPU seconds the lightweight pages took, from all connected to stopped."""
        return self._cpu.value


def _pages(url: str, n: int, ready, stop, received, cpu) -> None:
    asyncio.run(_main(url, n, ready, stop, received, cpu))


async def _main(url: str, n: int, ready, stop, received, cpu) -> None:
    protocol = Subprotocol(f"viser-v{viser.__version__}")
    sockets = [await websockets.connect(url, subprotocols=[protocol], max_size=None) for _ in range(n)]
    ready.set()
    cpu0 = time.process_time()
    counts = [0] * n
    tasks = [asyncio.create_task(_page(i, ws, counts)) for i, ws in enumerate(sockets)]
    while not stop.is_set():
        await asyncio.sleep(0.2)
    received.value = float(sum(counts))
    cpu.value = time.process_time() - cpu0
    for task in tasks:
        task.cancel()
    for ws in sockets:
        await ws.close()


async def _page(i: int, ws, counts: list[int]) -> None:
    camera = _camera()

    async def read() -> None:
        async for message in ws:
            counts[i] += len(message)

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


QUESTION = {
    "format": "apf-viz-lecture",
    "version": 1,
    "title": "Who moves?",
    "stops": [
        {
            "title": "Ten robots",
            "scenario": "Heart from 10 robots",
            "say": "Every light off.",
            "ask": {"kind": "robot"},
        }
    ],
}


def lecture_hall(
    n: int, args: list[str], start_record: str, own: bool = False, answering: int | None = None
) -> None:
    """The projector alone, then beside n class pages: each with a robot selected, or (``own``) each
    trying a run of its own, playing at the fastest an own run may; or (``answering``: that many of the
    n) a stop's question answered by every one of those pages, the others each trying a run of its own,
    and then how long the projector takes to show one answer more."""
    app = App(demo_session(), port=free_port(), verbose=False)
    if answering is not None:
        import json

        app.session.load_lecture("who.json", json.dumps(QUESTION).encode())
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
        rss_alone = _rss_mb()
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
        if own:
            app.session.pause()
            app.session.reset()  # each own run branches at the start: it plays the whole window
        for i, cid in enumerate(sorted(light)):
            if answering is not None:  # the first answer, the rest try runs of their own
                own = i >= answering
                if not own:
                    # a key each (these pages ask for no seat: the rate is measured, not the seats)
                    app.session.answer_question(f"page {cid}", str(i % len(robots)))
                    continue
            if own:  # Try it yourself, then Play at the fastest an own run may
                screen = app.screens[cid]
                app.own_runs.try_alone(screen)
                screen.session.set_speed(OWN_SPEED)
                screen.session.toggle_play()
                continue
            app.classroom.click(cid, robots[i % len(robots)])  # each has selected a robot of its own
        app.request_render()
        time.sleep(2.0)
        cpu0, wall0 = time.process_time(), time.perf_counter()
        owned = [x.own for x in app.classroom.own_pages() if x.own is not None]
        before = sum(run.engine.state.events for run in owned)
        full = _measure(app, projector, student, start_record)
        if own:
            played = sum(run.engine.state.events for run in owned) - before
            still = sum(run.playing for run in owned)
            print(f"(the {len(owned)} own runs played {played:,} events meanwhile; {still} still playing)")
        server_cpu = (time.process_time() - cpu0) / (time.perf_counter() - wall0)
        share = full[0] / alone[0] if alone[0] else float("nan")
        what = "each playing its own run" if own else "each a robot selected"
        if answering is not None:
            what = f"{answering} answered the question, {n - answering} each playing its own run"
        print(
            f"| 2 + {n} class pages ({what}) | {full[0]:.1f} ({share:.2f} of alone) | "
            f"{full[1]:.1f} | {full[2]:.1f} |"
        )
        connected = len(app.screens)
        held = time.perf_counter() - wall0
        if answering is not None:
            _spread_latency(app, projector)
        rss_with = _rss_mb()
        pages.stop()
        received = pages.received / max(1, n)
        print(
            f"({connected} pages connected; each lightweight page read {received / 1e6:.1f} MB; CPU while "
            f"measured: the server {server_cpu:.2f} cores, the {n} lightweight pages about "
            f"{pages.cpu / (held + 4.0):.2f})"
        )
        deadline = time.time() + 60
        while len(app.screens) > 2 and time.time() < deadline:
            time.sleep(0.2)
        time.sleep(2.0)
        import gc

        gc.collect()
        print(
            f"(server memory: {rss_alone:.0f} MB before the class, {rss_with:.0f} MB with it, "
            f"{_rss_mb():.0f} MB after its {n} pages left; {len(app.classroom.own_pages())} own runs left)"
        )
        browser.close()
    app.stop()


def _spread_latency(app: App, projector) -> None:
    """The projector presenting, the room's answers shown (B): from one answer more (a page answering)
    to the projector's caption counting it, five times."""
    projector.keyboard.press("p")
    projector.locator("[data-apf=answered]").wait_for(timeout=60_000)
    projector.keyboard.press("b")
    projector.locator("[data-apf=bar]").first.wait_for(timeout=60_000)
    poll = app.session.screen.poll
    assert poll is not None
    waits = []
    for i in range(5):
        count = poll.count + 1
        t0 = time.perf_counter()
        app.session.answer_question(f"bench page {i}", "1")
        app.request_render()
        projector.wait_for_function(
            "n => new RegExp('^' + n + '( of \\\\d+)? answered$').test("
            "(document.querySelector('[data-apf=answered]') || {}).innerText || '')",
            arg=count,
            timeout=30_000,
        )
        waits.append(time.perf_counter() - t0)
    print(
        f"(one answer more to the projector's caption counting it: {', '.join(f'{w:.2f}' for w in waits)} s)"
    )


def _rss_mb() -> float:
    """The server's resident memory (this process), in MB, after a full collection and with the C
    allocator's free pages given back (what is left is what the server holds, not what it once used)."""
    import ctypes
    import gc

    gc.collect()
    with contextlib.suppress(OSError):
        ctypes.CDLL("libc.so.6").malloc_trim(0)
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024
    return float("nan")


def _connect_and_wait(url: str, n: int, ready, sleep: float) -> None:
    """n connections that read nothing (a laptop asleep), held ``sleep`` seconds or until killed."""

    async def hold() -> None:
        protocol = Subprotocol(f"viser-v{viser.__version__}")
        sockets = [await websockets.connect(url, subprotocols=[protocol], max_size=None) for _ in range(n)]
        camera = _camera()
        for ws in sockets:  # a page reports its camera once it has loaded: the server then counts it in
            await ws.send(camera)
        ready.set()
        await asyncio.sleep(sleep)
        for ws in sockets:  # waking: read what is waiting, then leave
            try:
                while True:
                    await asyncio.wait_for(ws.recv(), timeout=2.0)
            except (TimeoutError, websockets.ConnectionClosed):
                pass

    asyncio.run(hold())


def churn(n: int, rounds: int = 3) -> None:
    """``--churn N``: N connections opened, then their process killed (no goodbye), ``rounds`` times,
    while the heart demo plays; the server's memory after each round, and whether every page was let go."""
    import gc
    import os
    import signal

    app = App(demo_session(), port=free_port(), verbose=False)
    url = app.addresses[1].replace("http://", "ws://").split("?")[0]
    app.session.set_speed(SPEED)
    app.session.toggle_play()
    time.sleep(2.0)
    gc.collect()
    print("| round | pages connected | pages left after the kill | server memory (MB) |")
    print("|---:|---:|---:|---:|")
    print(f"| before | 0 | 0 | {_rss_mb():.1f} |")
    for round_ in range(1, rounds + 1):
        ready = multiprocessing.Event()
        process = multiprocessing.Process(target=_connect_and_wait, args=(url, n, ready, 3600.0), daemon=True)
        process.start()
        ready.wait(120)
        deadline = time.time() + 60
        while len(app.screens) < n and time.time() < deadline:
            time.sleep(0.2)
        connected = len(app.screens)
        time.sleep(3.0)  # a few seconds of play with every one of them asleep
        assert process.pid is not None
        os.kill(process.pid, signal.SIGKILL)  # abruptly: no close handshake
        process.join()
        deadline = time.time() + 60
        while app.screens and time.time() < deadline:
            time.sleep(0.2)
        if app.session.engine.finished:
            app.session.reset()
            app.session.toggle_play()
        time.sleep(2.0)
        gc.collect()
        print(f"| {round_} | {connected} | {len(app.screens)} | {_rss_mb():.1f} |", flush=True)
    app.stop()


def _short_stays(url: str, n: int, batch: int) -> None:
    """n class pages, ``batch`` at a time, each at a fresh seat: a camera sent (the server counts the page
    in), 0.3 s of reading, a clean goodbye."""
    import secrets

    async def one() -> None:
        seat = url + "seat/" + secrets.token_hex(16)
        protocol = Subprotocol(f"viser-v{viser.__version__}")
        async with websockets.connect(seat, subprotocols=[protocol], max_size=None) as ws:
            await ws.send(_camera())
            with contextlib.suppress(TimeoutError, websockets.ConnectionClosed):
                while True:
                    await asyncio.wait_for(ws.recv(), timeout=0.3)

    async def main() -> None:
        for _ in range(0, n, batch):
            await asyncio.gather(*(one() for _ in range(batch)))

    asyncio.run(main())


def short_stays(n: int, rounds: int = 4) -> None:
    """``--short N``: N short class pages in ``rounds`` rounds (each in a process of its own, as laptops
    are): the server's memory and the pages it still holds after each round, settled."""
    import gc

    app = App(demo_session(), port=free_port(), verbose=False)
    url = app.addresses[1].replace("http://", "ws://").split("?")[0].rstrip("/") + "/"

    def round_of(pages: int) -> None:
        process = multiprocessing.Process(target=_short_stays, args=(url, pages, 20), daemon=True)
        process.start()
        process.join()
        deadline = time.time() + 60
        while app.screens and time.time() < deadline:
            time.sleep(0.2)
        gc.collect()

    round_of(60)  # warm: the first pages make what every later page reuses
    print("| pages so far | pages held | server memory (MB) |")
    print("|---:|---:|---:|")
    print(f"| 0 | {len(app.screens)} | {_rss_mb():.1f} |", flush=True)
    for r in range(1, rounds + 1):
        round_of(n // rounds)
        print(f"| {r * (n // rounds)} | {len(app.screens)} | {_rss_mb():.1f} |", flush=True)
    app.stop()


def _event_numbers(frame: bytes, event_uuid: list[str]) -> list[int]:
    """The page's ``Event`` values a frame sets, in order (the first frames make the number input and
    name its uuid: kept in ``event_uuid``)."""
    import msgspec
    import zstandard

    size, compressed = int.from_bytes(frame[:8], "little"), int.from_bytes(frame[8:16], "little")
    raw = zstandard.ZstdDecompressor().decompress(frame[16 : 16 + compressed], size)
    if (event_uuid[0].encode() if event_uuid else b"Event") not in raw:
        return []  # most frames: decoded no further (the client's own work, not the server's)
    inner = msgspec.msgpack.decode(raw)
    values = []
    for m in inner["messages"]:
        if m.get("type") == "GuiNumberMessage" and m.get("props", {}).get("label") == "Event":
            event_uuid[:] = [m["uuid"]]
            values.append(int(m["value"]))
        elif (
            m.get("type") == "GuiUpdateMessage"
            and event_uuid
            and m.get("uuid") == event_uuid[0]
            and "value" in m.get("updates", {})
        ):
            values.append(int(m["updates"]["value"]))
    return values


def _sleep_and_wake(url: str, n: int, asleep, wake, target, report) -> None:
    """n pages that read as a page does for 3 s, then nothing (``asleep`` set) until ``wake``: then each
    reads what is waiting and on, until its Event number is ``target`` (the run's, paused); the seconds
    each took are put on ``report``."""

    async def awake(ws, uuid: list[str]) -> None:
        await ws.send(_camera())
        end = time.time() + 3.0
        while time.time() < end:
            with contextlib.suppress(TimeoutError):
                _event_numbers(await asyncio.wait_for(ws.recv(), 0.5), uuid)

    async def catch_up(ws, uuid: list[str], t0: float) -> tuple[float, bool]:
        """Seconds until the page shows ``target``, and whether it had to connect anew (a page that
        read nothing for long misses the server's keepalive pings and is let go; viser's page then
        connects again, as this one does)."""
        again = False
        while True:
            try:
                frame = await asyncio.wait_for(ws.recv(), 60)
            except websockets.ConnectionClosed:
                again, uuid = True, []
                protocol = Subprotocol(f"viser-v{viser.__version__}")
                ws = await websockets.connect(url, subprotocols=[protocol], max_size=None)
                await ws.send(_camera())
                continue
            values = _event_numbers(frame, uuid)
            if values and values[-1] == target.value:
                took = time.perf_counter() - t0
                await ws.close()  # after the time is taken: the close handshake may wait (close_timeout)
                return took, again

    async def main() -> None:
        protocol = Subprotocol(f"viser-v{viser.__version__}")
        # A queue of one frame: asleep, the page stops reading its socket almost at once (as a laptop's
        # browser does), and what the server sends waits in the sockets' buffers, then in the server.
        connect = websockets.connect
        sockets = [await connect(url, subprotocols=[protocol], max_size=None, max_queue=1) for _ in range(n)]
        uuids: list[list[str]] = [[] for _ in sockets]
        await asyncio.gather(*(awake(ws, u) for ws, u in zip(sockets, uuids, strict=True)))
        asleep.set()  # from now on nothing is read: the sockets' buffers fill, the server's sends wait
        while not wake.is_set():
            await asyncio.sleep(0.05)
        t0 = time.perf_counter()
        results = await asyncio.gather(
            *(catch_up(ws, u, t0) for ws, u in zip(sockets, uuids, strict=True)), return_exceptions=True
        )
        report.put([r if isinstance(r, tuple) else (float("nan"), False) for r in results])

    asyncio.run(main())


def sleep_and_wake(n: int, sleep: float) -> None:
    """``--wake N``: N class pages fall asleep (read nothing) for ``sleep`` seconds while the heart demo
    plays, the run is then paused, and they wake: how long until each shows the run's event; meanwhile
    the server's frames/s and memory."""
    app = App(demo_session(), port=free_port(), verbose=False)
    url = app.addresses[1].replace("http://", "ws://").split("?")[0]
    asleep, wake = multiprocessing.Event(), multiprocessing.Event()
    target = multiprocessing.Value("q", -1)
    report: multiprocessing.Queue[list[tuple[float, bool]]] = multiprocessing.Queue()
    process = multiprocessing.Process(
        target=_sleep_and_wake, args=(url, n, asleep, wake, target, report), daemon=True
    )
    process.start()
    asleep.wait(120)
    app.session.set_speed(SPEED)
    before, frames, t0 = _rss_mb(), app.frames, time.perf_counter()
    app.session.toggle_play()
    end = t0 + sleep
    while time.perf_counter() < end:
        if app.session.engine.finished:  # the heart formed: again, so the run keeps changing
            app.session.reset()
            app.session.toggle_play()
        time.sleep(0.2)
    rate = (app.frames - frames) / (time.perf_counter() - t0)
    app.session.pause()
    app.request_render()  # as the Pause button does: every page's panel brought up to date
    during = _rss_mb()
    target.value = app.session.engine.state.events
    time.sleep(0.5)  # the paused run's last frame drawn
    wake.set()
    results = report.get(timeout=180)
    process.join(30)
    times = sorted(t for t, _ in results)
    again = sum(1 for _, a in results if a)
    print(
        "| pages asleep | asleep for | server frames/s meanwhile | memory before → asleep (MB) |"
        " woken: showing the run's event after (s), median / slowest | of them connected anew |"
    )
    print("|---:|---:|---:|---:|---:|---:|")
    print(
        f"| {n} | {sleep:.0f} s | {rate:.1f} | {before:.0f} → {during:.0f} | "
        f"{statistics.median(times):.2f} / {times[-1]:.2f} | {again} |"
    )
    app.stop()
