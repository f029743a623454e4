"""The visualiser's commands: one shared run, the drafts being drawn, the mode, and each connected
browser's own state (its selection). What the screen shows is the view model's
(:mod:`apf_viz.workbench.view_model`): :meth:`Session.view` asks it, for one browser, under the run's lock.

No viser here, and no particular algorithm. The work is split by job:
:class:`~apf_viz.workbench.run_controller.RunController` (engine, adversary, play),
:class:`~apf_viz.workbench.editor.Editor` (drafts), :mod:`apf_viz.workbench.loader` (files in),
:mod:`apf_viz.workbench.screen_state` (the screen's state, shared and per browser).
Every call is serialised by the run's lock, so all connected browsers drive the same run safely.

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
    """What every browser sees and drives: the run, the drafts, the mode and the selection."""
