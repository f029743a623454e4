"""The classroom around the shared run, with no viser: pages and roles, seats, who drives, answers, the
room's list, runs of one's own, the play clock (workbench/classroom/classroom.py)."""

from apf_viz.workbench.classroom.classroom import Classroom, Note
from apf_viz.workbench.classroom.own_runs import EXTRA_EVENTS, MAX_OWN_RUNS, OWN_SHARE, OWN_SPEED
from apf_viz.workbench.classroom.page_run import SHARED_ONLY, PageRun
from apf_viz.workbench.classroom.pages import Page
from apf_viz.workbench.classroom.play_clock import FPS, ClassTurns, StepPacer, play_budget
from apf_viz.workbench.classroom.roles import Roles
from apf_viz.workbench.classroom.room_list import RoomPage

__all__ = [
    "EXTRA_EVENTS",
    "FPS",
    "MAX_OWN_RUNS",
    "OWN_SHARE",
    "OWN_SPEED",
    "SHARED_ONLY",
    "ClassTurns",
    "Classroom",
    "Note",
    "Page",
    "PageRun",
    "Roles",
    "RoomPage",
    "StepPacer",
    "play_budget",
]
