"""Adversary: the scheduler and its seed, whether no-op activations are kept, Manual's clicks and who is
next for what, and Verify (every schedule of a small start)."""

from __future__ import annotations

from apf_viz.core.formats import InputError
from apf_viz.core.schedulers import BY_HAND
from apf_viz.ui.panels.context import PanelContext, put, tell
from apf_viz.workbench.session import SCHEDULER_LABELS
from apf_viz.workbench.verifier import MAX_K
from apf_viz.workbench.view_model import SessionView


def scheduler_label(name: str) -> str:
    return next(k for k, v in SCHEDULER_LABELS.items() if v == name)


class AdversaryFolder:
    def __init__(self, gui, ctx: PanelContext) -> None:
        self.ctx = ctx
        s = ctx.session
        with ctx.driving(gui.add_folder("Adversary")):
            self.scheduler = gui.add_dropdown(
                "Scheduler", tuple(SCHEDULER_LABELS), initial_value=scheduler_label(s.scheduler_name)
            )
            self.scheduler.on_update(ctx.from_browser(lambda e: s.set_scheduler(self.scheduler.value)))
            self.seed = gui.add_number("Seed", initial_value=s.seed, step=1)
            self.seed.on_update(ctx.from_browser(lambda e: s.set_seed(self.seed.value)))
            self.all_activations = gui.add_checkbox(
                "All activations",
                initial_value=not s.config.skip_noops,
                hint="keep the cycles that change nothing (a robot waking to a view it answers with "
                "'same light, stay'); off: the scheduler passes those robots over (the run restarts)",
            )
            self.all_activations.on_update(ctx.from_browser(self._on_all_activations))
            self.click = gui.add_dropdown(
                "Click",
                ("advance", "select"),
                initial_value="advance",
                visible=False,
                hint="Manual: a click on a robot runs its next phase (advance) or only selects it (select)",
            )
            self.click.on_update(
                ctx.from_browser(lambda e: s.set_click_advances(self.click.value == "advance"))
            )
            self.next_phase = gui.add_markdown("")
            # A schedule apf-viz adversary wrote: played from the start, its cost against the built-ins'.
            found = ctx.driving(
                gui.add_upload_button(
                    "Load the worst found", mime_type="*/*", hint="a schedule apf-viz adversary wrote"
                ),
                shared=True,
            )
            found.on_upload(self._load_found)
            self.found = gui.add_markdown("")
            self._verify_controls(gui)

    def _verify_controls(self, gui) -> None:
        self.verify = gui.add_button(
            "Verify",
            hint=f"explore every schedule of this start and pattern (k ≤ {MAX_K}), as apf-viz check does",
        )
        self.verify.on_click(self.ctx.guard(self._on_verify, "Verify"))
        self.ctx.driving(self.verify, shared=True)
        self.cancel_verify = gui.add_button("Cancel verification", visible=False)
        self.cancel_verify.on_click(self.ctx.guard(lambda e: self.ctx.verifier.cancel(), "Verify"))
        self.verify_status = gui.add_markdown("")

    def _load_found(self, event) -> None:
        f = event.target.value
        self.ctx.guard(lambda e: self.ctx.session.load_schedule(f.name, f.content), "Worst found")(event)

    def _on_all_activations(self, event) -> None:
        keep = bool(self.all_activations.value)
        if keep != (not self.ctx.session.config.skip_noops):
            self.ctx.session.set_all_activations(keep)

    def _on_verify(self, event) -> None:
        if self.ctx.in_own_run():  # the verifier is the shared run's, one at a time for the room
            raise InputError("Verify is the lecture's: not in a run of your own")
        why_not = self.ctx.verifier.start(event.client)
        if why_not:
            tell(event.client, "Verify", why_not, error=True)
        self.ctx.changed()

    def refresh(self, view: SessionView) -> None:
        s = self.ctx.session
        v = self.ctx.verifier.shown()
        running = v is not None and v.state == "running"
        if v is None:
            put(self.verify_status, content="")
        elif running:
            self.verify_status.content = (
                f"Verifying… **{v.states:,}** states, frontier {v.frontier:,}, {v.rate:,.0f} states/s"
            )
        else:
            put(self.verify_status, content=f"Verify: {v.text}")
        if self.cancel_verify.visible != running:
            self.cancel_verify.visible = running
        manual = view.scheduler in BY_HAND
        if self.click.visible != manual:
            self.click.visible = manual
        click = "advance" if view.click_advances else "select"
        if self.click.value != click:
            self.click.value = click
        if self.all_activations.value == s.config.skip_noops:
            self.all_activations.value = not s.config.skip_noops
        if self.scheduler.value != scheduler_label(view.scheduler):
            self.scheduler.value = scheduler_label(view.scheduler)
        put(self.next_phase, content=view.next_phases)
        put(self.found, content=found_words(view))


def found_words(view: SessionView) -> str:
    """A worst found being played: what the search says of it, and the run's moves per k·D so far."""
    if not view.trace_note.startswith("the worst "):  # adversary's, or check --worst's (core/schedule.Found)
        return ""
    state = (view.outcome or "running").upper()
    return (
        f"**{view.trace_note[0].upper()}{view.trace_note[1:]}.** Now: {view.moves:,} moves, "
        f"**moves/(k·D) = {view.moves_per_kD:.3f}**, {state} at event {view.event:,}."
    )
