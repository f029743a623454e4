"""Builds the viser server around one shared :class:`Session`, and serves it.

Threads: viser runs callbacks on its own threads; they only call the session and ask for a render.
One render thread owns the scene: it advances the run while playing and draws at most ``FPS`` frames a
second, each frame one atomic update, so clicks stay responsive while the engine plays.
"""

from __future__ import annotations

import gc
import threading
import time
import warnings

import viser

from apf_viz.core.engine import Engine
from apf_viz.ui import broadcast, viser_compat
from apf_viz.ui.browser_screen import BrowserScreen, inside
from apf_viz.ui.network import check_listen, reachable_host
from apf_viz.ui.network import free_port as free_port  # where tests and benchmarks find it
from apf_viz.ui.own_runs import OwnRuns
from apf_viz.ui.page_errors import quiet_page_errors
from apf_viz.ui.panels import Panels, SharedVerifier, tell
from apf_viz.ui.scene import Bounds, SceneRenderer, grown_box, ray_through
from apf_viz.ui.scene.compare_pair import ComparePair
from apf_viz.ui.seat import seat_token
from apf_viz.workbench.classroom import Classroom, Note, Roles
from apf_viz.workbench.classroom.play_clock import FPS, STEP_SHARE, StepPacer, play_budget
from apf_viz.workbench.config import SessionConfig, session_from_config
from apf_viz.workbench.screen_state import Role
from apf_viz.workbench.seats import Seats
from apf_viz.workbench.session import Session
from apf_viz.workbench.session.demo import demo_session as demo_session  # where tests and scripts find it

# A step that leaves this many robots to decide anew (a light a crowd sees: about 0.1 ms each) is shown
# before the next step pays for them: the page sees the light a frame's worth of decisions sooner.
DEAR_DECISIONS = 200


def settle_memory() -> None:
    """Collect garbage once, then exempt what survives from later collections (``gc.freeze``): a full
    collection scans every object a large run holds (its history, the decisions' memo), about 60 ms at
    1,000 robots, and came about once a second of play, each one a frame the page waited for. Done
    while nobody watches frames go by: as the loop starts and whenever play stops (``unfreeze`` first,
    so nothing unreachable stays frozen for long). As play starts, :func:`freeze_for_play`."""
    gc.unfreeze()
    gc.collect()
    gc.freeze()


def freeze_for_play() -> None:
    """Exempt every object made since the last settle from the collections play will trigger, without
    collecting (a full collection there was the first frame's 45–60 ms wait at 1,000 robots). What play
    then makes is collected as usual; garbage frozen here waits for the settle when play stops."""
    gc.freeze()


class App:
    """The visualiser: server, the shared scene, each browser's panel and selection, the render loop."""

    def __init__(
        self,
        session: Session,
        host: str = "127.0.0.1",
        port: int = 8080,
        verbose: bool = True,
        present: bool = False,
        roles: Roles | None = None,
        seats_per_address: int = 1,
    ) -> None:
        self.session = session
        # The class around the run (workbench/classroom): which pages present (those opened at the
        # presenter address), the seats issued here, who drives, answers, the room, runs of one's own.
        self.classroom = Classroom(session, roles or Roles(), Seats(seats_per_address))
        self.roles, self.seats = self.classroom.roles, self.classroom.seats
        self._host = host
        self.present = present  # a browser that opens while a lecture is followed opens presenting it
        broadcast.install()  # the shared scene's windows encoded once for all pages, not once a page
        self.missing = viser_compat.missing()  # viser's insides this viser lacks (startup_line says which)
        quiet_page_errors()  # a page's malformed message: one line on the terminal, not a traceback
        # A page that leaves while its frame is drawn (a laptop closed, or asleep past the keepalive) gets
        # that frame's last updates on a closed connection: expected, and nothing is lost (a page that
        # comes back connects anew and is sent the whole state), so not a warning in the lecturer's terminal.
        warnings.filterwarnings("ignore", r"Queued a \w+ on a closed connection", UserWarning)
        self.server = viser.ViserServer(host=host, port=port, label="apf-viz", verbose=verbose)
        gui = self.server.gui
        gui.configure_theme(control_width="large")
        # Docked, not floating: the panel takes its own strip of the window, so it never hides part of
        # the run, and the browser no longer renders (and, without a GPU, reads back) the pixels under it.
        gui.main_panel.dock_right()
        self.renderer = SceneRenderer(self.server, root="/shared", selection=False)
        self.pair = ComparePair(self.renderer)  # the run, and under Compare the second run to its right
        self.verifier = SharedVerifier(session, self.request_render)
        self.screens: dict[int, BrowserScreen] = {}
        self._screens_lock = threading.Lock()
        # Pages that left before their screen was made: viser runs a page's connect and disconnect
        # callbacks on a pool of threads, so a page that stays a moment (a reload, a script) can be gone
        # while its panels are still being built. Each id here is taken out by its own connect callback.
        self._gone: set[int] = set()
        self._dirty = threading.Event()  # a frame is wanted
        self._changed = False  # and it shows a change every page is owed (not only the class's turns)
        self._stop = threading.Event()
        self._framed_engine = session.engine  # the run the cameras were last framed on
        self._initial_bounds: tuple[float, float, float, float] | None = None
        self._framed_end = False  # the cameras were framed on the run's end
        self._framed_twin = session.screen.twin  # the Compare the cameras were last framed with
        self._framed_playing = False  # the run was playing when the cameras were last kept framed
        self._framed_stop: tuple[int, int] | None = None  # the lecture and stop they were kept for
        self.frames = 0
        self.own_runs = OwnRuns(self.classroom, self._screens, self.request_render)  # Try it yourself
        self.server.scene.on_click()(self._on_click)
        self.server.on_client_connect(self._connect)
        self.server.on_client_disconnect(self._disconnect)
        self._render()
        self._frame_initial()
        self._thread = threading.Thread(target=self._loop, name="apf-viz-render", daemon=True)
        self._thread.start()

    @property
    def port(self) -> int:
        return self.server.get_port()

    @property
    def addresses(self) -> tuple[str, str]:
        """(presenter, class): the page addresses to open, on a host other machines reach."""
        return self.roles.addresses(reachable_host(self._host), self.port)

    def role_of(self, client) -> Role:
        """A page's role, from the path its websocket was opened at (the presenter address's secret); a
        class page where viser does not say (the presenter code stands in: :meth:`claim_presenter`)."""
        return self.roles.role_of(viser_compat.websocket_path(self.server, client.client_id))

    def seat_of(self, client_id: int) -> str | None:
        """The key a page's answers are held under: its seat (ui/seat.py), which a reload keeps; None for
        a page the server has not issued one yet. Where viser does not say the path, the page's
        connection (a reload is a new page: the startup line says what else is missing then)."""
        if self.by_code:
            return f"page {client_id}"
        return self.seats.key(seat_token(viser_compat.websocket_path(self.server, client_id)))

    def seat_offer(self, client) -> str | None:
        """A seat's token for a class page that has none (issued to the address it came from); None for a
        page that has one, a presenter's page, or where viser does not say the path."""
        if self.by_code or self.role_of(client) != "class" or self.seat_of(client.client_id) is not None:
            return None
        return self.seats.issue(viser_compat.remote_address(self.server, client.client_id))

    @property
    def by_code(self) -> bool:
        """Roles are claimed by the presenter code: this viser does not say which address a page used."""
        return any(a.name == "websocket path" for a in self.missing)

    @property
    def panels(self) -> Panels | None:
        """The presenter's panel (the first browser's), if it is connected."""
        return next((x.panels for x in self._screens() if x.state is self.session.presenter), None)

    def _screens(self) -> list[BrowserScreen]:
        with self._screens_lock:
            return list(self.screens.values())

    def _screen(self, client) -> BrowserScreen | None:
        with self._screens_lock:
            return self.screens.get(client.client_id) if client is not None else None

    def _connect(self, client) -> None:
        cid = client.client_id
        with self._screens_lock:
            if cid in self._gone:  # it left before this callback ran: nothing to make
                self._gone.discard(cid)
                return
        screen = BrowserScreen(self, client)
        screen.panels.ctx.try_alone = lambda: self.own_runs.try_alone(screen)
        screen.panels.ctx.back_to_lecture = lambda: self.own_runs.back(screen)
        with self._screens_lock:
            left = cid in self._gone
            self._gone.discard(cid)
            if not left:
                self.screens[cid] = screen
        if left:  # it left while its screen was made: let go of what the making joined
            self._let_go(cid)
            return
        screen.starts_framed(self.renderer)  # by the initial camera, which frames the run as it is
        if self.present and self.session.lecturer is not None:  # serve --lecture: the room's view
            screen.panels.presentation.present(True, client)
        self.request_render()

    def _disconnect(self, client) -> None:
        with self._screens_lock:
            if self.screens.pop(client.client_id, None) is None:
                self._gone.add(client.client_id)  # its connect callback has not finished: it lets go
                return
        self._let_go(client.client_id)

    def _let_go(self, client_id: int) -> None:
        self.classroom.leave(client_id)
        self.request_render()

    def request_render(self) -> None:
        """A frame, for a change every page is owed (the class pages get it in turn: :meth:`_due`)."""
        self._changed = True
        self._dirty.set()

    def frame_client(self, client) -> None:
        """Point this browser's camera at the whole run (robots and targets), as it is now."""
        screen = self._screen(client)
        if screen is not None:
            screen.frame(screen.renderer)
        else:
            self.renderer.frame_camera(client.camera)

    def frame_all(self) -> None:
        for screen in self._screens():
            screen.frame(screen.renderer)

    def drawn(self) -> dict[str, object]:
        """Every node drawn, by name: the shared run's, then each browser's selection layer."""
        screens = self._screens()
        nodes = self.renderer.nodes()
        for screen in screens:
            nodes.update(screen.selection.nodes())
        return nodes

    def stop(self) -> None:
        self._stop.set()
        self._thread.join(timeout=2)
        self.server.stop()

    # ------------------------------------------------------------------ events
    def point_at(self, client, screen: tuple[float, float]) -> tuple[float, float] | None:
        """The grid point under a point of a browser's canvas (0..1 each way from its top-left)."""
        try:
            origin, direction = ray_through(client.camera, screen)
        except (AssertionError, TypeError, ValueError):  # the browser has not reported its camera
            return None
        page = self._screen(client)
        return (page.renderer if page else self.renderer).point_of_ray(tuple(origin), tuple(direction))

    def _on_click(self, event) -> None:
        page = self._screen(event.client)  # a page trying its own run clicks in its own run
        renderer = page.renderer if page is not None else self.renderer
        cell = renderer.cell_of_ray(event.ray_origin, event.ray_direction)
        if cell is not None:
            key = event.client.client_id if event.client is not None else None
            try:  # a class page's click may answer a question, then acts on the run it shows
                notes = self.classroom.click(key, cell)
            except Exception as err:  # a click must never kill the server; only its browser is told
                notes = [Note("Click refused", str(err), error=True)]
            for note in notes:
                tell(event.client, note.title, note.text, error=note.error)
        if page is not None:
            page.changed()
        else:
            self.request_render()

    # ------------------------------------------------------------------ loop
    def _loop(self) -> None:
        """Play advances ``speed`` steps a second, but never spends more than ``STEP_SHARE`` of a frame
        stepping: a run too slow for the requested speed plays slower instead of starving the frames."""
        budget = 0.0
        last = tick = time.perf_counter()
        was_playing = False
        pacer = StepPacer()
        own_playing = False
        settle_memory()
        while not self._stop.is_set():
            if not self.session.playing and not own_playing:  # idle: sleep until something asks for a frame
                self._dirty.wait(timeout=1.0 / FPS)
            now = time.perf_counter()
            s = self.session
            if s.playing:
                if not was_playing:  # the first step at once
                    freeze_for_play()
                    now = last = time.perf_counter()
                    budget = 1.0
                budget = play_budget(budget, now - last, s.speed)
                deadline = now + STEP_SHARE / FPS
                while budget >= 1 and (t := time.perf_counter()) < deadline:
                    taken = s.play_steps(pacer.allowance(budget, deadline - t))
                    if not taken:  # the run ended, or Manual: play stops by itself
                        break
                    pacer.took(taken, time.perf_counter() - t)
                    budget -= taken
                    if s.engine.pending_decisions >= DEAR_DECISIONS:
                        break
                self.request_render()
            else:
                budget = 0.0
                if was_playing:
                    settle_memory()
            was_playing = s.playing
            # Pages' own runs: a share of a frame.
            own_playing = self.own_runs.play(self._screens(), 1.0 / FPS, now - last)
            if own_playing:
                self._dirty.set()
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
        everyone = self._screens()
        if self.own_runs.draw(everyone, 1.0 / FPS):  # pages trying their own runs: paced, within a share
            self._dirty.set()
        screens = [x for x in everyone if x.own is None]
        # While the run plays, a class page's panel and selection are brought up to date a dozen times a
        # second, in turn (the canvas they share is drawn for all at once, every frame): the projector
        # keeps its rate however large the class.
        due = self._due(screens)
        with self.session.lock:  # the run drawn and the run framed are one (a load may come in between)
            engine = self.session.engine
            run_view, views = self.session.views({x.client.client_id: x.state for x in due})
        cells = [x.cells for x in screens if x.cells is not None]
        self.renderer.view_cells = min(cells) if cells else None
        # Labels laid out for the framed page that shows them largest: apart there, apart on every page.
        heights = [h for x in screens if (h := x.text_height()) is not None]
        self.renderer.text_height = max(heights) if heights else None
        run_view, beside = self.classroom.beside(run_view)  # a laptop's own run on the projector, beside it
        with self.server.atomic():
            self.pair.render(run_view, self.session.config, beside)
        for screen in due:
            view = views[screen.client.client_id]
            try:
                with screen.client.atomic():
                    screen.selection.render(view)
                    screen.panels.refresh(view, following=screen.state.role == "class" and view.playing)
            except RuntimeError:  # the browser left while its frame was drawn
                continue
        self.frames += 1
        self._keep_framed(screens, engine)

    def _due(self, screens: list[BrowserScreen]) -> list[BrowserScreen]:
        """The pages whose panel and selection are brought up to date in this frame: every presenter
        page, and the class pages in turn (the classroom's play clock: the work of a frame does not grow
        with the class); while some are owed, another frame follows."""
        changed, self._changed = self._changed, False
        due = set(self.classroom.due([x.client.client_id for x in screens], changed))
        if self.classroom.turns.owing:
            self._dirty.set()
        return [x for x in screens if x.client.client_id in due]

    def _keep_framed(self, screens: list[BrowserScreen], engine: Engine) -> None:
        """A new run (Reset, a load, a switch of algorithm: a new engine) frames every browser's camera;
        a run growing out of a framed box (robots, targets, the leader's frame) re-frames the browsers
        whose camera is framed — one moved by hand is left alone — and the initial camera of browsers
        yet to join, with room to grow; a run that ends re-frames them on its end, which a camera
        framed for the run's widest moment (the line) shows small, and so does a run paused. While a
        person draws (an Edit mode) nothing is re-framed but by F."""
        b = self.renderer.bounds  # ``engine``'s, just drawn
        ended = engine.outcome is not None
        # A Compare begun or ended is a new picture too: both runs framed whole, not the first run's box
        # grown (which adds room to grow on every side the second run and its title reach).
        twin = self.session.screen.twin
        new = engine is not self._framed_engine or twin is not self._framed_twin
        if new or (ended and not self._framed_end):  # the run's last picture fills the framed cameras
            self._framed_engine, self._framed_end, self._framed_twin = engine, ended, twin
            self._frame_initial()
            for screen in screens:
                if new or screen.state.camera == "framed":
                    screen.frame(self.renderer)
            return
        self._framed_end = ended
        paused = self._framed_playing and not self.session.playing
        self._framed_playing = self.session.playing
        lecturer = self.session.lecturer  # a stop reached plays to it without Play: framed as a pause
        stop = (id(lecturer), lecturer.position) if lecturer is not None else None
        moved_on, self._framed_stop = stop != self._framed_stop, stop
        if (paused or (moved_on and not self.session.playing)) and self.session.mode == "run":
            # Play (or a stop's run to its moment) grew the framing with room to spare (robots drawn
            # small); paused, the run fills the cameras that follow it again, as it did before Play.
            self._frame_initial()
            for screen in screens:
                if screen.state.camera == "framed":
                    screen.frame(self.renderer)
            return
        if self.session.mode != "run":
            # Drawing: the camera stays where the person put it (F frames). Re-framed to a drawing
            # that grew, the pointer would land on other cells mid-stroke and paint far away.
            return
        if not inside(b, self._initial_bounds):
            f = self._initial_bounds
            self._frame_initial(None if f is None else grown_box(b, f))
        for screen in screens:
            f = screen.state.framed_bounds
            if screen.state.camera == "framed" and (f is None or not inside(b, f)):
                screen.frame(self.renderer, None if f is None else grown_box(b, f))

    def _frame_initial(self, bounds: Bounds | None = None) -> None:
        self.renderer.frame_initial_camera(self.server.initial_camera, bounds)
        self._initial_bounds = self.renderer.bounds if bounds is None else bounds
        self._dirty.set()  # labels are laid out for the framed zoom (scene.text_cells): once more


def serve(config: SessionConfig, *, host: str, port: int, seats_per_address: int = 1) -> int:
    """``apf-viz serve``: the session ``config`` describes, served until Ctrl+C. A bad address, file or
    lecture is one line before the server starts; a lecture's pages open presenting it."""
    check_listen(host, port)
    session = session_from_config(config)
    app = None
    try:  # Ctrl+C stops it quietly, however early: while the server starts, or at any time after
        app = App(
            session,
            host=host,
            port=port,
            verbose=False,
            present=config.lecture is not None,
            seats_per_address=seats_per_address,
        )
        presenter, follower = app.addresses
        print(f"apf-viz: serving on {host}:{app.port}  (Ctrl+C to stop)", flush=True)
        print(f"presenter: {presenter}", flush=True)
        print(f"class: {follower}", flush=True)
        said = viser_compat.startup_line(app.missing)
        if said is not None:
            print(said, flush=True)
        if app.by_code:
            print(f"presenter code: {app.roles.code}  (type it into Presenter code on a page)", flush=True)
        while True:
            time.sleep(3600)
    except KeyboardInterrupt:
        pass
    finally:
        if app is not None:
            app.stop()
    return 0
