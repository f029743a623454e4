"""Compare's two runs in one scene: the run, and the second run (the same start, pattern and adversary
under another algorithm) to its right, at a fixed distance, its labels laid out for the one camera's
zoom and clear of the first run's. The shared scene holds one pair, and so does each page trying a run
of its own."""

from __future__ import annotations

from apf_viz.ui.scene.renderer import SceneRenderer
from apf_viz.ui.scene.style import LABEL_ROOM
from apf_viz.workbench.run_config import RunConfig
from apf_viz.workbench.view_model import SessionView


class ComparePair:
    """Draws a view and, when it compares, its second run beside it (made on first need, cleared when
    the Compare ends); the first renderer's bounds then frame both."""

    def __init__(self, first: SceneRenderer) -> None:
        self.first = first
        self.second: SceneRenderer | None = None

    def render(self, view: SessionView, config: RunConfig, beside: str | None = None) -> None:
        """One frame of both; the caller wraps it in the scene's ``atomic()``. ``beside``: the second
        run is a class page's (workbench/classroom/room_list.py), titled so, and the first is the
        lecture's."""
        if beside is not None:
            state = view.outcome.upper() if view.outcome else "running"
            titles: tuple[str | None, str | None] = (f"the lecture's run · {state}", beside)
        elif view.compare is not None:
            titles = (compare_title("A", view), compare_title("B", view.compare))
        else:
            titles = (None, None)
        self.first.render(view, titles[0])
        other = view.compare
        if other is None:
            self.clear_second()
            return
        a = self.first
        if self.second is None:
            self.second = SceneRenderer(a.server, prefix="/compare", root=a.root)
        xs = [p[0] for p in (*config.robots, *config.pattern)]
        gap = max(xs) - min(xs) + len(config.robots) + 8
        self.second.fixed_origin = (a.origin[0] - gap, a.origin[1])
        # One camera shows both runs: the second's labels are laid out for the first's zoom.
        self.second.view_cells = a.view_cells if a.view_cells is not None else a.visible_height()
        self.second.text_height = a._text_height()
        self.second.render(other, titles[1], beside=a.label_boxes)
        b = self.second.bounds
        x0, y0, x1, y1 = a.bounds
        # Labels run to the right of what they name (numbers, "the leader's frame"): room for them.
        a.bounds = (min(x0, b[0]), min(y0, b[1]), max(x1, b[2]) + LABEL_ROOM, max(y1, b[3]))

    def clear_second(self) -> None:
        if self.second is not None:
            self.second.clear()
            self.second = None

    def clear(self) -> None:
        self.clear_second()
        self.first.clear()


def compare_title(side: str, view: SessionView) -> str:
    """A Compare run's title above it, in words a room reads: which algorithm, and how its run stands."""
    state = view.outcome.upper() if view.outcome else "running"
    # The title's gloss in brackets is left to the caption: the camera frames the runs, not their titles.
    name = (view.algorithm_title or view.algorithm).split(" (")[0]
    return f"{side}: {name} · {state}"
