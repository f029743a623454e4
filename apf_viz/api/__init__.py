"""apf-viz from Python: the same engine, budgets and schedulers as the command line.

- :func:`run` one run to its outcome, a :class:`Run` (its numbers, its events as a table, a figure, a
  page to show in a notebook, its trace);
- :func:`sweep` a grid of runs on Dask, a pandas DataFrame with ``apf-viz sweep``'s columns;
- :func:`check` every schedule of a small start, a :class:`Verdict` whose counterexample replays;
- :func:`hunt` every schedule of many generated starts, a DataFrame with ``apf-viz hunt``'s columns;
- :func:`adversary` the searched adversary, a :class:`Found` whose schedule replays;
- :func:`lecture_check` a lecture's stops, headless; :func:`plot` a sweep's table as figures.

docs/API.md documents each with an example a test runs.
"""

from apf_viz.api.adversaries import Found, adversary
from apf_viz.api.checks import Verdict, Worst, check
from apf_viz.api.hunts import hunt
from apf_viz.api.lectures import LectureChecked, lecture_check
from apf_viz.api.plots import plot
from apf_viz.api.runs import Run, Shown, run
from apf_viz.api.sweeps import sweep

__all__ = [
    "Found",
    "LectureChecked",
    "Run",
    "Shown",
    "Verdict",
    "Worst",
    "adversary",
    "check",
    "hunt",
    "lecture_check",
    "plot",
    "run",
    "sweep",
]
