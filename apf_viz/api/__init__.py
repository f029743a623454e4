"""apf-viz from Python: the same engine, budgets and schedulers as the command line.

- :func:`run` one run to its outcome, a :class:`Run` (its numbers, its events as a table, a figure, a
  page to show in a notebook, its trace);
- :func:`sweep` a grid of runs on Dask, a pandas DataFrame with ``apf-viz sweep``'s columns;
- :func:`check` every schedule of a small start, a :class:`Verdict` whose counterexample replays;
- :func:`hunt` every schedule of many generated starts, a DataFrame with ``apf-viz hunt``'s columns.

docs/API.md documents each with an example a test runs.
"""

from apf_viz.api.checks import Verdict, check
from apf_viz.api.hunts import hunt
from apf_viz.api.runs import Run, Shown, run
from apf_viz.api.sweeps import sweep

__all__ = ["Run", "Shown", "Verdict", "check", "hunt", "run", "sweep"]
