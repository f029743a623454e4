"""The GUI of one browser: a folder a module, each building its controls and refreshing itself from that
browser's :class:`~apf_viz.workbench.view_model.SessionView`.

Labels are part of the interface (people and the browser tests find controls by them): Step, Back,
Play/Pause, Speed, Reset, Timeline, Scheduler, Seed, Event, Mode, Follow presenter, and the file buttons.
Callbacks ignore programmatic updates (``event.client is None``), so refreshing a value from the session
never feeds back into it; what a callback has to say goes to the browser that caused it only.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Hashable
from typing import Protocol, cast

from apf_viz.ui.panels.adversary import AdversaryFolder
from apf_viz.ui.panels.algorithm import AlgorithmFolder
from apf_viz.ui.panels.compare import CompareFolder
from apf_viz.ui.panels.context import PanelContext, SharedVerifier, tell
from apf_viz.ui.panels.edit import MODE_LABELS, MODES, EditFolder
from apf_viz.ui.panels.files import FilesFolder, load_demo
from apf_viz.ui.panels.join import Join
from apf_viz.ui.panels.legend import LegendFolder
from apf_viz.ui.panels.moves import MovesFolder
from apf_viz.ui.panels.paper import PaperFolder
from apf_viz.ui.panels.presentation import Presentation
from apf_viz.ui.panels.presenter_code import Claim, PresenterCode
from apf_viz.ui.panels.question import QuestionFolder
from apf_viz.ui.panels.room import RoomFolder
from apf_viz.ui.panels.run import HistoryFolder, RunFolder
from apf_viz.ui.panels.selected import SelectedFolder
from apf_viz.ui.panels.shortcuts import Shortcuts
from apf_viz.ui.panels.why import WhyFolder
from apf_viz.workbench.classroom import Classroom
from apf_viz.workbench.session import Session
from apf_viz.workbench.view_model import SessionView

__all__ = ["MODES", "MODE_LABELS", "Panels", "SharedVerifier", "tell"]

# In this order on screen: what a lecture narrates first — Step, the outcome, Event, the last event in
# full, the selected robot and Why fit together on a 1024×768 projector's first screen — then the history,
# the legend, and the folders a lecture rarely needs, collapsed.
FOLDERS = (
    QuestionFolder,  # shown first (its folder's order), and only while a stop asks the class something
    RunFolder,
    SelectedFolder,
    WhyFolder,
    PaperFolder,
    HistoryFolder,
    LegendFolder,
    AdversaryFolder,
    AlgorithmFolder,
    CompareFolder,
    RoomFolder,  # the presenter's only
    EditFolder,
    FilesFolder,
    MovesFolder,
)


class Folder(Protocol):
    """A part of the panel: it shows what the browser's view says."""

    def refresh(self, view: SessionView) -> None: ...


# While playing, the Paper's pseudocode (re-highlighted as the actor changes), the History (timeline, log,
# stats) and the Moves chart are re-laid out and repainted by the page for each change, about a tenth of
# a software-rendered page's frame each (docs/PERFORMANCE.md): at most four times a second they follow.
SLOW_FOLDERS = (PaperFolder, HistoryFolder, MovesFolder, RoomFolder)
PLAYING_REFRESH_S = 0.25
FOLLOWING_FOLDERS = (RunFolder, SelectedFolder)  # what a class page following a played run keeps in step
FOLLOWING_REFRESH_S = 1.0


class Panels:
    """One browser's panel (``owner``: the viser client, or the server for a panel every browser
    shares); :meth:`refresh` shows that browser's view."""

    def __init__(
        self,
        owner,
        session: Session,
        changed: Callable[[], None],
        frame: Callable[[object], None] = lambda client: None,
        *,
        browser: Hashable | None = None,
        verifier: SharedVerifier | None = None,
        frame_all: Callable[[], None] = lambda: None,
        point_at: Callable | None = None,
        class_address: Callable[[], str] | None = None,
        classroom: Classroom | None = None,
        seat_offer: Callable[[], str | None] | None = None,
        claim_presenter: Claim | None = None,
    ) -> None:
        # Without a classroom (a panel of the server's own, a test), one around this run alone.
        classroom = classroom or Classroom(session)
        self.session = session = cast(Session, classroom.run_of(browser))
        self.ctx = PanelContext(
            session,
            browser,
            changed,
            frame,
            frame_all,
            verifier or SharedVerifier(classroom.shared, changed),
            classroom,
        )
        self.ctx.client = owner if browser is not None else None
        if point_at is not None:
            self.ctx.point_at = point_at
        if class_address is not None:
            self.ctx.class_address = class_address
        if seat_offer is not None:
            self.ctx.seat_offer = seat_offer
        self.presentation = Presentation(owner.gui, self.ctx)
        self.folders: list[Folder] = [folder(owner.gui, self.ctx) for folder in FOLDERS]
        self.join = Join(owner.gui, self.ctx)
        self.folders += [Shortcuts(owner.gui, self.ctx), self.presentation, self.join]
        self.folders.append(PresenterCode(owner.gui, self.ctx, claim_presenter))
        self._slow_refreshed = -PLAYING_REFRESH_S  # when the slow folders last refreshed (monotonic s)
        self._driving_shown = (True, True)  # the driving controls (and the shared run's alone) shown

    @property
    def presenting(self) -> bool:
        """This browser is in presentation mode (its camera leaves room for the caption)."""
        return self.presentation.on

    def refresh(self, view: SessionView, following: bool = False) -> None:
        """Every folder shows the view; while the run plays, the folders that redraw much of the page for
        a change (:data:`SLOW_FOLDERS`) at most every :data:`PLAYING_REFRESH_S`. A paused run, a step or
        the frame that ends Play refreshes them all. ``following``: a class page following the played run
        (one of many) keeps only the Run and Selected folders in step; the others every
        :data:`FOLLOWING_REFRESH_S`."""
        now = time.monotonic()
        period = FOLLOWING_REFRESH_S if following else PLAYING_REFRESH_S
        slow = not view.playing or now - self._slow_refreshed >= period
        if slow:
            self._slow_refreshed = now
        fast = FOLLOWING_FOLDERS if following else ()
        for folder in self.folders:
            if slow or (isinstance(folder, fast) if following else not isinstance(folder, SLOW_FOLDERS)):
                folder.refresh(view)
        self._show_driving()

    def _show_driving(self) -> None:
        """The controls that change the shared run, shown only where this page may drive it (a class
        page follows the lecture unless the presenter lets the class drive)."""
        drives = self.ctx.drives()
        shared = not self.ctx.in_own_run()  # a run of its own has no files, lectures or Demo
        shown = (drives, shared)
        if shown != self._driving_shown:
            self._driving_shown = shown
            for handle in self.ctx.driving_handles:
                handle.visible = drives
            for handle in self.ctx.shared_handles:
                handle.visible = drives and shared

    def _folder(self, kind: type):
        return next(f for f in self.folders if isinstance(f, kind))

    @property
    def legend(self):
        """The legend's HTML element."""
        return self._folder(LegendFolder).html

    @property
    def _recorder(self):
        """This browser's GIF recording, if one runs."""
        return self._folder(FilesFolder).recorder

    _load_demo = staticmethod(load_demo)
