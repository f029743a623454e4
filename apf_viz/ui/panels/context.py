"""What every panel folder is given: the session, the browser it belongs to, and how to ask for a frame,
point a camera, tell a browser something and verify the run."""

from __future__ import annotations

import weakref
from collections.abc import Callable, Hashable
from dataclasses import dataclass, field

from apf_viz.core.formats import MAX_TRACE_BYTES, InputError
from apf_viz.ui import viser_compat
from apf_viz.workbench.classroom import Classroom
from apf_viz.workbench.screen_state import BrowserState
from apf_viz.workbench.session import Session
from apf_viz.workbench.verifier import Status, Verifier
from apf_viz.workbench.view_model import SessionView

FOLLOWING = (
    "this page follows the lecture: the presenter drives the shared run (select a robot to see what it "
    "sees; the presenter may let the class drive)"
)

# Each browser's last notification under each title: a new one replaces it, so that a key pressed ten
# times (Next stage) shows one message, the latest, instead of a pile over the canvas.
_shown: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def put(handle, **props) -> None:
    """Set only the properties of a panel element that changed: viser casts every assigned value against
    its type hints before it compares, which, for every page of a class in every frame, costs more than
    the comparison done here."""
    for name, value in props.items():
        if getattr(handle, name) != value:
            setattr(handle, name, value)


def tell(client, title: str, body: str, error: bool = False) -> None:
    """A notification for one browser (None: a programmatic change, told to nobody); it closes itself,
    and replaces the browser's previous one under the same title."""
    if client is None:
        return
    mine = _shown.setdefault(client, {})
    previous = mine.pop(title, None)
    if previous is not None and not viser_compat.notification_removed(previous):
        previous.remove()
    mine[title] = client.add_notification(
        title, body, auto_close_seconds=8.0, color="red" if error else "blue"
    )


class SharedVerifier:
    """One verification of the shared run at a time; its progress shows in every browser, its result is
    told to the browser that started it, and a counterexample is loaded into the run for Step to follow."""

    def __init__(self, session: Session, changed: Callable[[], None]) -> None:
        self.session, self.changed = session, changed
        self.verifier = Verifier(self._on_status)
        self._client = None

    @property
    def status(self) -> Status:
        return self.verifier.status

    def start(self, client) -> str | None:
        config = self.session.config
        why_not = self.verifier.start(config, self.session.run.plugins)
        if why_not is None:
            self._client = client
            self._verified = _problem_of(config)
        return why_not

    def shown(self) -> Status | None:
        """The status to show: a verification running, or the verdict on the problem now on screen (a
        counterexample loaded keeps it; another start, pattern, algorithm or semantics does not)."""
        status = self.verifier.status
        if status.state == "running" or (status.text and self._verified == _problem_of(self.session.config)):
            return status
        return None

    _verified: tuple | None = None

    def cancel(self) -> None:
        self.verifier.cancel()

    def _on_status(self, status: Status) -> None:
        """From the verifier's thread: progress, or the end (a counterexample is loaded into the run)."""
        if status.state != "running":
            if status.trace is not None:
                try:
                    self.session.load_trace("counterexample.jsonl", status.trace.encode(), MAX_TRACE_BYTES)
                except InputError as e:  # cannot happen for the engine's own replay; said if it does
                    tell(self._client, "Verify", f"the counterexample did not load: {e}", error=True)
            tell(self._client, "Verify", status.text, error=status.state == "violation")
        self.changed()


def _problem_of(config) -> tuple:
    return (config.robots, config.pattern, config.y_up, config.algorithm, config.light_semantics)


@dataclass
class PanelContext:
    """A browser's panel: whose it is, and the App's services."""

    session: Session  # the page's door to the run it drives (workbench/classroom/page_run.py)
    browser: Hashable | None  # the viser client id (None: a panel built on the server's own GUI)
    changed: Callable[[], None]  # ask for a frame
    frame: Callable[[object], None]  # point one browser's camera at the whole run
    frame_all: Callable[[], None]  # point every browser's camera at the whole run
    verifier: SharedVerifier
    classroom: Classroom  # the class around the shared run: roles, who drives, answers, the room
    toggle_presentation: Callable = lambda event=None: None  # set by the browser's Presentation
    presenting: Callable[[], bool] = lambda: False  # set by the browser's Presentation
    release_focus: Callable[[], None] = lambda: None  # set by the Run folder: the keys drive the run again
    client: object | None = None  # the viser client whose panel this is (its own scene: a dragged box)
    # The grid point under a point of a browser's canvas (0..1 each way), or None: the App's projection.
    point_at: Callable[[object, tuple[float, float]], tuple[float, float] | None] = lambda client, point: None
    # The address the class's laptops open (workbench/classroom/roles.py).
    class_address: Callable[[], str] = lambda: ""
    seat_offer: Callable[[], str | None] = lambda: None  # a seat's token for a class page that has none
    driving_handles: list = field(default_factory=list)  # shown only where the browser may drive
    shared_handles: list = field(default_factory=list)  # shown only where it drives the shared run
    # Try it yourself (ui/own_runs.py): a class page branches a run of its own, and comes back; the App
    # sets these (a panel without an App has no own runs).
    try_alone: Callable[[], str] = lambda: "no runs of one's own here"
    back_to_lecture: Callable[[], str] = lambda: "this page follows the lecture"

    def drives(self) -> bool:
        """Whether this browser may change the run it shows (a presenter page, the class when the
        presenter lets it, or a page's own run)."""
        return self.classroom.may_drive(self.browser)

    @property
    def state(self) -> BrowserState:
        """This page's state on the run it shows (its selection, whether it follows, its camera)."""
        return self.classroom.state(self.browser)

    def view(self) -> SessionView:
        """What this page shows now."""
        return self.session.view(self.state)

    def in_own_run(self) -> bool:
        """Whether this page drives a run of its own (no files, lectures or Demo there)."""
        page = self.classroom.page(self.browser)
        return page is not None and page.own is not None

    @property
    def shared(self) -> Session:
        """The shared run, which holds the stop's question, also for a page trying a run of its own."""
        return self.classroom.shared

    def laptop(self) -> int | None:
        """This page's number in the Room's list, for a class page (None: a presenter): shown on the
        page, so that the lecturer can hand the run to the laptop whose student raised a hand."""
        return self.classroom.laptop(self.browser) if self.browser is not None else None

    def answer_key(self) -> str | None:
        """The key this page's answers are held under: its seat (None: none yet)."""
        page = self.classroom.page(self.browser)
        return page.seat if page is not None else None

    def may(self, event) -> bool:
        """:meth:`drives`; when it may not, the browser that tried is told so, and its controls are
        put back to the run's values (a frame)."""
        if self.drives():
            return True
        tell(event.client, "Following the lecture", FOLLOWING)
        self.changed()
        return False

    def driving(self, handle, shared: bool = False):
        """A control (or folder) that changes the run: shown only where this browser may drive;
        ``shared``: only where it drives the shared run (files, lectures: not in a run of its own)."""
        (self.shared_handles if shared else self.driving_handles).append(handle)
        return handle

    def guard(self, fn: Callable, title: str = "apf-viz", mine: bool = False) -> Callable:
        """Run a callback; bad input, or what it has to say (a returned string), is told to the browser
        that caused it, not to every browser (a laptop's hint must not pop up on the projector). Always
        re-render afterwards. A callback that changes the shared run runs only for a browser that may
        drive it; ``mine``: it acts on this browser alone (its camera, its presentation mode)."""

        def wrapped(event) -> None:
            if not mine and not self.may(event):
                return
            try:
                said = fn(event)
                if isinstance(said, str) and said:
                    tell(event.client, title, said)
            except (InputError, ValueError) as err:
                tell(event.client, "Refused", str(err), error=True)
            kept = self.session.take_kept_drafts_note()
            if kept:  # a Demo or a file replaced a drawing that was never run: say where it went
                tell(event.client, "Your drawing is kept", kept)
            self.changed()

        return wrapped

    def step(self, event) -> None:
        """Step (the button or the key): one event, or in Manual this browser's selected robot's next
        phase; why nothing ran goes to the browser that asked."""
        s = self.session
        s.pause()
        if not s.step(self.state):
            tell(event.client, "Step", s.why_not_step())

    def from_browser(self, fn: Callable, title: str = "apf-viz", mine: bool = False) -> Callable:
        """:meth:`guard`, for a control's update: programmatic updates (``event.client is None``, a value
        refreshed from the session) never feed back into it."""
        guarded = self.guard(fn, title, mine)

        def wrapped(event) -> None:
            if event.client is not None:
                guarded(event)

        return wrapped
