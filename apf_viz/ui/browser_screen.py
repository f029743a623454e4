"""One connected browser: its panel, its selection layer, and its camera (framed on the run, or left
where the hand moved it)."""

from __future__ import annotations

from typing import Protocol

import numpy as np

from apf_viz.ui.caption_room import CAPTION_ROOM, PHONE_SHEET_ROOM
from apf_viz.ui.panels import Panels, SharedVerifier
from apf_viz.ui.panels.presentation import upright_phone
from apf_viz.ui.recorder import canvas_size
from apf_viz.ui.scene import (
    NARROW_ASPECT,
    Bounds,
    SceneRenderer,
    camera_aspect,
    camera_cells,
    scene_detail,
    text_cells,
)
from apf_viz.ui.scene.compare_pair import ComparePair
from apf_viz.ui.scene.selection import SelectionRenderer
from apf_viz.workbench.classroom import Classroom, Page
from apf_viz.workbench.screen_state import BrowserState, Role
from apf_viz.workbench.session import Session
from apf_viz.workbench.view_model import SessionView


class Host(Protocol):
    """What a browser's screen is given by the app that serves it (ui/app.py)."""

    classroom: Classroom
    renderer: SceneRenderer
    verifier: SharedVerifier

    @property
    def by_code(self) -> bool: ...

    def request_render(self) -> None: ...
    def role_of(self, client) -> Role: ...
    def seat_of(self, client_id: int) -> str | None: ...
    def seat_offer(self, client) -> str | None: ...
    def frame_client(self, client) -> None: ...
    def frame_all(self) -> None: ...
    def point_at(self, client, screen: tuple[float, float]) -> tuple[float, float] | None: ...
    @property
    def addresses(self) -> tuple[str, str]: ...


class BrowserScreen:
    """One connected browser: its panel, its selection layer in its own scene, and its state."""

    def __init__(self, app: Host, client) -> None:
        self.client = client
        # This page in the class: its role, its seat, its state, its own run (workbench/classroom).
        self.page: Page = app.classroom.join(
            client.client_id, app.role_of(client), app.seat_of(client.client_id)
        )
        self._classroom = app.classroom
        self.selection = SelectionRenderer(client, app.renderer, root="/own")
        self.own: SceneRenderer | None = None  # its own run, drawn in its own scene
        self._own_pair: ComparePair | None = None  # that run, and its Compare's second run beside it
        self._own_twin: object | None = None  # the Compare its camera was last framed with
        self._hiding: list = []  # its own frame over the shared scene's root, which hides it here
        self._request_render = app.request_render
        # Its own run's picture and panel may differ from what the page was last sent: its own commands,
        # clicks, zoom and play set it; an own run unchanged is not drawn again (ui/own_runs.py).
        self.stale = True
        self.drawn_at = 0.0  # when its own run was last drawn (perf_counter): own runs are paced
        self.panels = Panels(
            client,
            app.classroom.shared,
            self.changed,
            app.frame_client,
            browser=client.client_id,
            verifier=app.verifier,
            frame_all=app.frame_all,
            point_at=app.point_at,
            class_address=lambda: app.addresses[1],
            classroom=app.classroom,
            seat_offer=lambda: app.seat_offer(client),
            claim_presenter=self._claim if app.by_code else None,
        )
        self._sent: list[np.ndarray] = []  # the positions of the last poses sent to it
        self._renderer = app.renderer
        self._framed_aspect = NARROW_ASPECT  # the canvas shape its camera was last framed for
        self._reported: np.ndarray | None = None  # the camera position it last reported
        self.cells: float | None = None  # how many cells tall its camera shows (scene.camera_cells)
        client.camera.on_update(self._camera_moved)

    def changed(self) -> None:
        """This page did something (a command, a click, a zoom): a frame, in which its own run, if it
        tries one, is drawn anew, and its panel before the rest of the class's."""
        self.stale = True
        self._classroom.turns.hurry(self.page.key)
        self._request_render()

    def text_height(self) -> float | None:
        """A label's height in cells on this page, if its camera is framed on the run (a camera moved by
        hand is the person's own: the shared labels are not laid out for it)."""
        if self.cells is None or self.state.camera != "framed" or self.own is not None:
            return None
        return text_cells(self.cells, canvas_size(self.client)[0])

    @property
    def state(self) -> BrowserState:
        """This page's state on the shared run: its selection, whether it follows, its camera."""
        return self.page.state

    @property
    def session(self) -> Session:
        """The run this page shows: its own, or the shared one."""
        return self.page.own if self.page.own is not None else self._classroom.shared

    def _claim(self, code: str) -> str:
        """The presenter code typed on this page (where viser does not say the address it opened)."""
        said = self._classroom.claim_presenter(self.page.key, code)
        if self.own is not None and self.page.own is None:  # a page presenting has no run of its own
            self.detach_own()
        self.changed()
        return said

    @property
    def renderer(self) -> SceneRenderer:
        """What draws the run it shows: its own run's renderer, or the shared one."""
        return self.own if self.own is not None else self._renderer

    def attach_own(self, own: Session) -> None:
        """From now on this page shows and drives ``own``: the shared run is hidden on this page alone (a
        frame of its own of the same name shadows the shared one: viser draws a page's own variant of a
        node before the one every page shares), and the shared run's selection layer is cleared."""
        self._hiding = [self.client.scene.add_frame("/shared", show_axes=False, visible=False)]
        self.selection.clear()
        self.own = SceneRenderer(self.client, root="/mine")
        self._own_pair = ComparePair(self.own)
        self._own_twin = own.screen.twin

    def draw_own(self, view: SessionView) -> None:
        """Its own run, and its Compare's second run beside it, in its own scene; a Compare begun or
        ended there frames its camera anew (on both runs, or on the one)."""
        assert self._own_pair is not None
        self._own_pair.render(view, self.session.config)
        twin = self.session.screen.twin
        if twin is not self._own_twin:
            self._own_twin = twin
            self.frame(self.renderer)

    def detach_own(self) -> None:
        """Back to the shared run: its own run and everything drawn of it are dropped."""
        if self._own_pair is not None:
            self._own_pair.clear()
        self.own = self._own_pair = self._own_twin = None
        for frame in self._hiding:
            frame.remove()
        self._hiding = []

    def _camera_moved(self, camera) -> None:
        """A camera that leaves the pose it was last framed to was moved by hand: it is left there while
        the run grows, until a new run starts or Frame run is pressed. Reports are matched against the
        poses sent: the browser reports each, possibly late (a loaded machine, a page still loading), and
        until it has reported the latest, what it reports may predate that framing (a drag still in
        flight when Frame run was pressed): not the hand's."""
        try:
            position = np.asarray(camera.position, dtype=float)
        except (AssertionError, TypeError, ValueError):
            return
        cells, self.cells = self.cells, camera_cells(camera)
        if self.cells is not None and (cells is None or scene_detail(cells) != scene_detail(self.cells)):
            self.changed()  # zoomed in or out past where the y-axis diamonds or outlines are drawn
        elif self.cells is not None and cells is not None and abs(self.cells - cells) > 0.02 * cells:
            self._request_render()  # the labels are laid out for the zoom the page now shows
        hand = self._acknowledged and not any(_same_pose(position, p) for p in self._sent)
        self._reported = position
        if hand:
            self.state.camera = "moved"
            return
        if self.state.camera == "framed" and abs(camera_aspect(camera) - self._framed_aspect) > 0.02:
            # The canvas changed shape (the panel docked, a window resized, a first report): the framing
            # was fitted to another width.
            self.frame(self.renderer)

    @property
    def _acknowledged(self) -> bool:
        """The page's camera is where it was last sent, by its own last report. Derived from the two, not
        kept: a pose sent again, or sent back to where the page already is, moves no camera and brings
        no report, and the page's last report still says it is there."""
        last = self._reported
        return last is not None and bool(self._sent) and _same_pose(last, self._sent[-1])

    def _sending(self, position) -> None:
        self._sent = [*self._sent[-7:], np.asarray(position, dtype=float)]

    def starts_framed(self, renderer: SceneRenderer) -> None:
        self._framed_aspect = NARROW_ASPECT  # the initial camera's
        self._sending(renderer.framed_pose[0])
        self.state.camera = "framed"
        self.state.framed_bounds = renderer.bounds

    def frame(self, renderer: SceneRenderer, bounds: Bounds | None = None) -> None:
        """Frame its camera on the run, or on ``bounds`` (the run with room to grow)."""
        if upright_phone(*canvas_size(self.client)):
            room = PHONE_SHEET_ROOM  # the run above the sheet, caption or not (the caption is in it)
        else:
            room = CAPTION_ROOM if self.panels.presenting else 0.0
        self.panels.presentation.fit(self.client)  # the caption across the canvas as it is now
        position, self._framed_aspect = renderer.frame_camera(self.client.camera, room, bounds)
        if position is not None:
            self._sending(position)
        self.state.camera = "framed"
        self.state.framed_bounds = renderer.bounds if bounds is None else bounds


def _same_pose(position: np.ndarray, sent: np.ndarray) -> bool:
    return bool(np.abs(position - sent).max() <= 1e-3 * max(1.0, abs(sent[2])))


def inside(box: tuple[float, float, float, float], framed: tuple[float, float, float, float] | None) -> bool:
    """Whether ``box`` lies inside the ``framed`` one (whose camera shows it whole, with a margin)."""
    if framed is None:
        return False
    return box[0] >= framed[0] and box[1] >= framed[1] and box[2] <= framed[2] and box[3] <= framed[3]
