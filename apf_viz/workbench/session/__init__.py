"""The visualiser's commands on one run: the run, the drafts being drawn, the mode. A Session is one run:
the shared one the projector shows, or a class page's own (workbench/classroom, which keeps the pages,
their states and who may drive, hands each page its run). What the screen shows is the view model's
(:mod:`apf_viz.workbench.view_model`): :meth:`Session.view` asks it, for one page's state, under the
run's lock.

No viser here, and no particular algorithm. The work is split by job:
:class:`~apf_viz.workbench.run_controller.RunController` (engine, adversary, play),
:class:`~apf_viz.workbench.editor.Editor` (drafts), :mod:`apf_viz.workbench.loader` (files in),
:mod:`apf_viz.workbench.screen_state` (the screen's state, shared and per browser).
Every call is serialised by the run's lock, so all the pages that drive it do so safely.

The session is the one object pages and scripts command (each command takes the lock once, and a panel
needs one handle). The commands are grouped by what they act on, a module each: the run, the drafts,
files, a lecture. Each group subclasses :class:`~apf_viz.workbench.session.core.SessionCore`, where the
state they share is declared once; the lecture's commands build on the run's and the files' (they drive
them), so no group declares another's members again (tests/test_house.py).
"""

from apf_viz.workbench.session.core import SCHEDULER_LABELS
from apf_viz.workbench.session.edit_commands import EditCommands
from apf_viz.workbench.session.lecture_commands import LectureCommands

__all__ = ["SCHEDULER_LABELS", "Session"]


class Session(LectureCommands, EditCommands):
    """One run and what is drawn and said about it: the run, the drafts, the mode, the presenter's
    selection, a lecture's stop and its question."""
