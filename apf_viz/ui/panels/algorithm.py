"""Algorithm: the algorithm or a variant of it, and the light semantics; switching restarts the run."""

from __future__ import annotations

from apf_viz.algorithms import ALGORITHMS
from apf_viz.ui.panels.context import PanelContext
from apf_viz.ui.presenter import SessionView


class AlgorithmFolder:
    def __init__(self, gui, ctx: PanelContext) -> None:
        self.ctx = ctx
        s = ctx.session
        with gui.add_folder("Algorithm", expand_by_default=False):
            self.algorithm = gui.add_dropdown("Algorithm", self._names(), initial_value=s.algorithm_name)
            self.algorithm.on_update(ctx.from_browser(self._on_algorithm))
            self.variant = gui.add_text(
                "Variant",
                initial_value=s.algorithm_name,
                hint="edit the name and press Use variant, e.g. apf-opaque-grid@G1,G2,LA "
                "(docs/ALGORITHM.md), "
                "or two lights as one colour: apf-opaque-grid+merge(leader1=decider)",
            )
            gui.add_button("Use variant").on_click(
                ctx.guard(lambda e: s.set_algorithm(self.variant.value.strip()))
            )
            self.semantics = gui.add_dropdown(
                "Light semantics", ("compute", "lc-atomic"), initial_value=s.config.light_semantics
            )
            self.semantics.on_update(ctx.from_browser(self._on_semantics))
        self._shown = s.algorithm_name

    def _names(self, current: str | None = None) -> tuple[str, ...]:
        s = self.ctx.session
        names = [*ALGORITHMS, *(n for n in s.run.plugins if ":" not in n)]
        current = current or s.algorithm_name
        return tuple(names if current in names else [*names, current])

    def _on_algorithm(self, event) -> None:
        if self.algorithm.value != self.ctx.session.algorithm_name:
            self.ctx.session.set_algorithm(self.algorithm.value)

    def _on_semantics(self, event) -> None:
        if self.semantics.value != self.ctx.session.config.light_semantics:
            self.ctx.session.set_light_semantics(self.semantics.value)

    def refresh(self, view: SessionView) -> None:
        s = self.ctx.session
        if self._shown != s.algorithm_name:  # the run's algorithm changed, by whichever control
            self._shown = s.algorithm_name
            self.algorithm.options = self._names(s.algorithm_name)
            self.algorithm.value = s.algorithm_name
            self.variant.value = s.algorithm_name  # the field follows the run's algorithm
        if self.semantics.value != s.config.light_semantics:
            self.semantics.value = s.config.light_semantics
