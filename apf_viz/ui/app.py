"""Builds the viser server around one shared :class:`Session`, and serves it.

Threads: viser runs callbacks on its own threads; they only call the session and ask for a render.
One render thread owns the scene: it advances the run while playing and draws at most ``FPS`` frames a
second, each frame one atomic update, so clicks stay responsive while the engine plays.
"""

from __future__ import annotations

import argparse
import socket
import threading
import time
from pathlib import Path

import viser

from apf_viz.algorithms import DEFAULT_ALGORITHM, algorithm_from_command_line
from apf_viz.core.formats import (
    MAX_TRACE_BYTES,
    InputError,
    check_sizes,
    load_pattern,
    load_robots,
    load_trace,
)
from apf_viz.demos import DEMO_PATTERN, DEMO_START
from apf_viz.ui.panels import Panels, tell
from apf_viz.ui.scene import SceneRenderer
from apf_viz.ui.session import Session

FPS = 30
STEP_SHARE = 0.6  # of each frame, at most, goes to stepping the engine while playing


def free_port(host: str = "127.0.0.1") -> int:
    """A TCP port nothing listens on now: for servers started side by side (tests, benchmarks, scripts)."""
    with socket.socket() as sock:
        sock.bind((host, 0))
        return sock.getsockname()[1]


class App:
    """The visualiser: server, scene, panels and the play/render loop."""

    def __init__(
        self, session: Session, host: str = "127.0.0.1", port: int = 8080, verbose: bool = True
    ) -> None:
        self.session = session
        self.server = viser.ViserServer(host=host, port=port, label="apf-viz", verbose=verbose)
        self.renderer = SceneRenderer(self.server)
        self.compare_renderer: SceneRenderer | None = None  # Compare: the second run, to the right
        self.panels = Panels(self.server, session, self.request_render, self.frame_client)
        self._dirty = threading.Event()
        self._stop = threading.Event()
        self._framed: tuple[float, float, float, float] | None = None
        self._framed_engine = session.engine  # the run the cameras were last framed on
        self.frames = 0
        self.server.scene.on_click()(self._on_click)
        self._render()
        self.renderer.frame_initial_camera(self.server.initial_camera)
        self._framed = self.renderer.bounds
        self._thread = threading.Thread(target=self._loop, name="apf-viz-render", daemon=True)
        self._thread.start()

    @property
    def port(self) -> int:
        return self.server.get_port()

    def request_render(self) -> None:
        self._dirty.set()

    def frame_client(self, client) -> None:
        """Point this browser's camera at the whole run (robots and targets), as it is now."""
        self.renderer.frame_camera(client.camera)

    def stop(self) -> None:
        self._stop.set()
        self._thread.join(timeout=2)
        self.server.stop()

    # ------------------------------------------------------------------ events
    def _on_click(self, event) -> None:
        cell = self.renderer.cell_of_ray(event.ray_origin, event.ray_direction)
        if cell is not None:
            try:
                self.session.click(cell)
            except Exception as err:  # a click must never kill the server; only its browser is told
                tell(event.client, "Click refused", str(err), error=True)
        self.request_render()

    # ------------------------------------------------------------------ loop
    def _loop(self) -> None:
        """Play advances ``speed`` steps a second, but never spends more than ``STEP_SHARE`` of a frame
        stepping: a run too slow for the requested speed plays slower instead of starving the frames."""
        budget = 0.0
        last = tick = time.perf_counter()
        while not self._stop.is_set():
            if not self.session.playing:  # idle: sleep until a click or a callback asks for a frame
                self._dirty.wait(timeout=1.0 / FPS)
            now = time.perf_counter()
            s = self.session
            if s.playing:
                budget = min(budget + (now - last) * s.speed, max(1.0, s.speed / FPS))
                deadline = now + STEP_SHARE / FPS
                while budget >= 1 and time.perf_counter() < deadline:
                    budget -= 1
                    if not s.play_step():  # the run ended, or Manual: play stops by itself
                        break
                self._dirty.set()
            else:
                budget = 0.0
            last = now
            if self._dirty.is_set():
                self._dirty.clear()
                self._render()
            # Frames are paced here, once: at most FPS a second, whether playing or not. The ticks are
            # absolute, so a sleep that overshoots (a busy machine) shortens the next one instead of
            # lowering the rate; a loop that fell a whole frame behind starts a fresh schedule.
            tick = max(tick + 1.0 / FPS, time.perf_counter() - 1.0 / FPS)
            time.sleep(max(0.0, tick - time.perf_counter()))

    def _render(self) -> None:
        view = self.session.view()
        with self.server.atomic():
            self.renderer.render(view, f"A: {view.algorithm}" if view.compare else None)
            self._render_compare(view)
            self.panels.refresh(view)
        self.frames += 1
        if self._needs_reframe():
            self.renderer.frame_initial_camera(self.server.initial_camera)
            for client in self.server.get_clients().values():
                self.renderer.frame_camera(client.camera)
            self._framed = self.renderer.bounds

    def _render_compare(self, view) -> None:
        """The second run of Compare beside the first, at a fixed distance to its right (the width of
        start ∪ pattern plus room for the runs to spread); the cameras frame both."""
        other = view.compare
        if other is None:
            if self.compare_renderer is not None:
                self.compare_renderer.clear()
                self.compare_renderer = None
            return
        if self.compare_renderer is None:
            self.compare_renderer = SceneRenderer(self.server, prefix="/compare")
        c = self.session.config
        xs = [p[0] for p in (*c.robots, *c.pattern)]
        gap = max(xs) - min(xs) + len(c.robots) + 8
        a = self.renderer
        self.compare_renderer.fixed_origin = (a.origin[0] - gap, a.origin[1])
        outcome = f" · {other.outcome.upper()}" if other.outcome else ""
        self.compare_renderer.render(other, f"B: {other.algorithm}{outcome}")
        b = self.compare_renderer.bounds
        x0, y0, x1, y1 = a.bounds
        a.bounds = (min(x0, b[0]), min(y0, b[1]), max(x1, b[2]), max(y1, b[3]))

    def _needs_reframe(self) -> bool:
        """Keep the run framed: re-frame when a new run starts (Reset, a load, a switch of algorithm: a
        new engine) and when something leaves the framed box as the run grows."""
        b = self.renderer.bounds
        engine = self.session.engine
        if engine is not self._framed_engine:
            self._framed_engine = engine
            return True
        if self._framed is None:
            self._framed = b
            return False
        f = self._framed
        return b[0] < f[0] - 2 or b[1] < f[1] - 2 or b[2] > f[2] + 2 or b[3] > f[3] + 2


def demo_session(**options) -> Session:
    """The built-in demo: a heart from 10 robots. ``options`` go to :class:`Session`."""
    robots = load_robots(DEMO_START)
    pattern = load_pattern(DEMO_PATTERN)
    options.setdefault("seed", 1)
    return Session(
        [tuple(p) for p in robots.robots],
        [tuple(p) for p in pattern.points],
        y_up=robots.flips(options["seed"]),
        **options,
    )


def session_from_args(args: argparse.Namespace) -> Session:
    """The session ``apf-viz serve`` starts with. ``--algorithm`` may load a plug-in (the command line is
    the one place allowed to); a trace then names only built-ins or that plug-in."""
    algorithm, plugins = algorithm_from_command_line(args.algorithm or DEFAULT_ALGORITHM)
    options = {"algorithm": algorithm.name, "scheduler": args.scheduler, "seed": args.seed}
    if args.trace:
        session = demo_session(**options, plugins=plugins)
        path = Path(args.trace)
        load_trace(path)  # validates the file with a one-line error before the UI starts
        session.load_trace(path.name, path.read_bytes(), MAX_TRACE_BYTES)  # the command line's own file
        return session
    robots = load_robots(args.robots) if args.robots else load_robots(DEMO_START)
    pattern = load_pattern(args.pattern) if args.pattern else load_pattern(DEMO_PATTERN)
    if args.pattern is None and len(pattern.points) != len(robots.robots):
        raise InputError(
            f"{args.robots}: {len(robots.robots)} robots, but the default pattern (the demo's heart) has "
            f"{len(pattern.points)} points: pass --pattern"
        )
    check_sizes(robots, pattern, str(args.pattern or DEMO_PATTERN))
    return Session(
        [tuple(p) for p in robots.robots],
        [tuple(p) for p in pattern.points],
        y_up=robots.flips(args.seed),
        light_semantics=args.light_semantics,
        plugins=plugins,
        **options,
    )


def check_listen(host: str, port: int) -> None:
    """Refuse, with one line, an address the server could not listen on (a bad host, a port in use),
    before viser tries in a thread of its own."""
    try:
        family, kind, proto, _, address = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)[0]
        with socket.socket(family, kind, proto) as probe:
            probe.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            probe.bind(address)
    except (OSError, OverflowError, UnicodeError) as e:
        raise InputError(f"cannot listen on {host}:{port}: {getattr(e, 'strerror', None) or e}") from None


def serve(args: argparse.Namespace) -> int:
    check_listen(args.host, args.port)
    session = session_from_args(args)
    app = App(session, host=args.host, port=args.port, verbose=False)
    print(f"apf-viz: serving on http://{args.host}:{app.port}  (Ctrl+C to stop)", flush=True)
    try:
        while True:
            time.sleep(3600)
    except KeyboardInterrupt:
        app.stop()
    return 0
