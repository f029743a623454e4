"""Moves over events: the run's moves against its events, as a line plot."""

from __future__ import annotations

import numpy as np

from apf_viz.ui.panels.context import PanelContext
from apf_viz.workbench.view_model import SessionView


class MovesFolder:
    def __init__(self, gui, ctx: PanelContext) -> None:
        with gui.add_folder("Moves over events", expand_by_default=False):
            self.plot = gui.add_uplot(
                (np.array([0.0]), np.array([0.0])),
                ({"label": "event"}, {"label": "moves", "stroke": "#d33", "width": 2}),
                scales={"x": {"time": False}},  # uPlot reads x as timestamps unless told otherwise
                aspect=2.0,
            )

    def refresh(self, view: SessionView) -> None:
        series = np.array(view.move_series, dtype=np.float64).reshape(-1, 2)  # at most SERIES_POINTS
        self.plot.data = (series[:, 0], series[:, 1])
