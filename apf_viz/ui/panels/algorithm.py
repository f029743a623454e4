"""Algorithm: the algorithm or a variant of it (a resolution set, two lights as one colour), and the light
semantics; switching restarts the run."""

from __future__ import annotations

from apf_viz.ui.panels.context import PanelContext
from apf_viz.workbench.algorithm_choice import algorithm_names, light_merges, merge_of, with_merge
from apf_viz.workbench.view_model import SessionView


class AlgorithmFolder:
    def __init__(self, gui, ctx: PanelContext) -> None:
        self.ctx = ctx
        s = ctx.session
        with ctx.driving(gui.add_folder("Algorithm", expand_by_default=False)):
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
            self.merge = gui.add_dropdown(
                "Two lights as one",
                self._merges(),
                initial_value=merge_of(s.algorithm_name),
                hint="show one light as another, to every robot and to itself: does the algorithm still "
                "work with one light fewer? (apf-viz lights tries them all: docs/LIGHTS.md)",
            )
            self.merge.on_update(ctx.from_browser(self._on_merge))
            self.semantics = gui.add_dropdown(
                "Light semantics", ("compute", "lc-atomic"), initial_value=s.config.light_semantics
            )
            self.semantics.on_update(ctx.from_browser(self._on_semantics))
        self._shown = s.algorithm_name

    def _names(self, current: str | None = None) -> tuple[str, ...]:
        s = self.ctx.session
        return algorithm_names(current or s.algorithm_name, s.run.plugins)

    def _merges(self) -> tuple[str, ...]:
        return light_merges(self.ctx.session.engine.algorithm)

    def _on_merge(self, event) -> None:
        s = self.ctx.session
        wanted = with_merge(s.algorithm_name, self.merge.value)
        if wanted != s.algorithm_name:
            s.set_algorithm(wanted)

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
            merges = self._merges()
            if tuple(self.merge.options) != merges:
                self.merge.options = merges
            self.merge.value = merge_of(s.algorithm_name)
        if self.semantics.value != s.config.light_semantics:
            self.semantics.value = s.config.light_semantics
