"""The GUI: folders of controls wired to the :class:`Session` with one-line callbacks.

Labels are part of the interface (people and the browser tests find controls by them): Step, Back,
Play/Pause, Speed, Reset, Timeline, Scheduler, Seed, Event, Mode, and the file buttons.
Callbacks ignore programmatic updates (``event.client is None``), so refreshing a value from the
session never feeds back into it.
"""

from __future__ import annotations

import threading
from collections.abc import Callable

import numpy as np
import viser
import viser.uplot
from viser._messages import GuiSliderMark

from apf_viz.algorithms import ALGORITHMS
from apf_viz.core.formats import MAX_TRACE_BYTES, InputError
from apf_viz.demos import demo_files, scenarios
from apf_viz.ui.image import png_on_white
from apf_viz.ui.recorder import MAX_SECONDS, RECORD_FPS, GifRecorder, render_view
from apf_viz.ui.run_controller import MAX_SPEED
from apf_viz.ui.session import SCHEDULER_LABELS, Session, SessionView
from apf_viz.ui.verifier import MAX_K, Verifier
from apf_viz.ui.verifier import Status as VerifyStatus
from apf_viz.ui.why import legend_html, symbol_html, why_markdown

MODES = {"Run": "run", "Edit pattern": "edit-pattern", "Edit robots": "edit-robots"}
MODE_LABELS = {v: k for k, v in MODES.items()}


def tell(client, title: str, body: str, error: bool = False) -> None:
    """A notification for one browser (None: a programmatic change, told to nobody)."""
    if client is not None:
        client.add_notification(title, body, auto_close_seconds=8.0, color="red" if error else "blue")


class Panels:
    """Builds the GUI once; :meth:`refresh` shows a new view."""

    def __init__(
        self,
        server: viser.ViserServer,
        session: Session,
        changed: Callable[[], None],
        frame: Callable[[object], None] = lambda client: None,
    ) -> None:
        self.server, self.session, self.changed = server, session, changed
        self.frame = frame  # points one browser's camera at the whole run
        self._recorder: GifRecorder | None = None
        self.verifier = Verifier(self._verified)
        self._verify_client = None
        self._recording_lock = threading.Lock()
        gui = server.gui
        gui.configure_theme(control_width="large")
        # Docked, not floating: the panel takes its own strip of the window, so it never hides part of
        # the run, and the browser no longer renders (and, without a GPU, reads back) the pixels under it.
        gui.main_panel.dock_right()
        # The legend first, so that it is on screen whenever the run is; folders a lecture rarely needs
        # start collapsed, so that Last event and Why fit on a 1024×768 projector.
        with gui.add_folder("Legend"):
            self.legend = gui.add_html("")
        with gui.add_folder("Run"):
            self.demo = gui.add_dropdown("Demo", ("—", *scenarios()), initial_value="—")
            self.demo.on_update(self._on_demo)
            self.demo_note = gui.add_markdown("")
            row = gui.add_button_group("Controls", ("Step", "Back", "Play", "Reset"))
            row.on_click(self._on_control)
            self.controls = row
            self.speed = gui.add_slider(
                "Speed", min=1, max=int(MAX_SPEED), step=1, initial_value=10, hint="steps per second"
            )
            self.speed.on_update(lambda e: self._set_speed(e))
            self.timeline = gui.add_slider(
                "Timeline",
                min=0,
                max=1,
                step=1,
                initial_value=0,
                hint="scrub the history; stepping from the past branches",
            )
            self.timeline.on_update(self._on_timeline)
            jumps = gui.add_button_group("Go to", ("Next move", "Next stage", "Frame run"))
            jumps.on_click(self._on_jump)
            self.trace = gui.add_markdown("")
            self.branch = gui.add_button(
                "Branch here", visible=False, hint="leave the trace: the scheduler runs"
            )
            self.branch.on_click(self._guard(lambda e: self.session.branch_here()))
            self.aside = gui.add_markdown("")
            self.restore = gui.add_button(
                "Return to set-aside branch",
                visible=False,
                hint="go back to the recorded steps the last branch dropped, and follow them",
            )
            self.restore.on_click(self._guard(lambda e: self.session.return_to_set_aside()))
            self.banner = gui.add_markdown("")
            self.event = gui.add_number("Event", initial_value=0, disabled=True)
            self.last_event = gui.add_text("Last event", initial_value="", disabled=True)
            self.log = gui.add_markdown("")
            self.stats = gui.add_markdown("")
            self.numbers = gui.add_checkbox(
                "Numbers", initial_value=True, hint="each robot's number beside it"
            )
            self.numbers.on_update(self._on_numbers)
        with gui.add_folder("Adversary"):
            self.scheduler = gui.add_dropdown(
                "Scheduler", tuple(SCHEDULER_LABELS), initial_value=self._scheduler_label()
            )
            self.scheduler.on_update(self._on_scheduler)
            self.seed = gui.add_number("Seed", initial_value=session.seed, step=1)
            self.seed.on_update(self._on_seed)
            self.all_activations = gui.add_checkbox(
                "All activations",
                initial_value=not session.config.skip_noops,
                hint="keep the cycles that change nothing (a robot waking to a view it answers with "
                "'same light, stay'); off: the scheduler passes those robots over (the run restarts)",
            )
            self.all_activations.on_update(self._on_all_activations)
            self.click = gui.add_dropdown(
                "Click",
                ("advance", "select"),
                initial_value="advance",
                visible=False,
                hint="Manual: a click on a robot runs its next phase (advance) or only selects it (select)",
            )
            self.click.on_update(self._on_click_mode)
            self.next_phase = gui.add_markdown("")
            self.verify = gui.add_button(
                "Verify",
                hint=f"explore every schedule of this start and pattern (k ≤ {MAX_K}), as apf-viz check does",
            )
            self.verify.on_click(self._on_verify)
            self.cancel_verify = gui.add_button("Cancel verification", visible=False)
            self.cancel_verify.on_click(lambda e: self.verifier.cancel())
            self.verify_status = gui.add_markdown("")
        with gui.add_folder("Selected robot"):
            self.caption = gui.add_markdown("")
        with gui.add_folder("Why"):
            self.why = gui.add_markdown("Select a robot to see why it acted.")
        with gui.add_folder("Algorithm", expand_by_default=False):
            self.algorithm = gui.add_dropdown(
                "Algorithm", self._algorithm_names(), initial_value=session.algorithm_name
            )
            self.algorithm.on_update(self._on_algorithm)
            self.variant = gui.add_text(
                "Variant",
                initial_value=session.algorithm_name,
                hint="edit the name and press Use variant, e.g. apf-opaque-grid@G1,G2,LA (docs/ALGORITHM.md)",
            )
            gui.add_button("Use variant").on_click(
                self._guard(lambda e: self.session.set_algorithm(self.variant.value.strip()))
            )
            self.semantics = gui.add_dropdown(
                "Light semantics", ("compute", "lc-atomic"), initial_value=session.config.light_semantics
            )
            self.semantics.on_update(self._on_semantics)
        with gui.add_folder("Compare", expand_by_default=False):
            self.compare_with = gui.add_text(
                "Compare with",
                initial_value="apf-opaque-grid-literal",
                hint="a second algorithm or variant (e.g. apf-opaque-grid@G1,G2): the same start, pattern "
                "and adversary, drawn to the right and stepping with the run",
            )
            compare = gui.add_button_group("Compare runs", ("Compare", "Stop comparing"))
            compare.on_click(self._on_compare)
            self.compare_status = gui.add_markdown("")
        with gui.add_folder("Edit", expand_by_default=False):
            self.mode = gui.add_dropdown("Mode", tuple(MODES), initial_value="Run")
            self.mode.on_update(self._on_mode)
            self.counts = gui.add_markdown("")
            gui.add_button("Clear pattern").on_click(self._guard(lambda e: self.session.clear_pattern()))
        with gui.add_folder("Files", expand_by_default=False):
            self.demo_pattern = gui.add_dropdown("Demo pattern", ("—", *demo_files()), initial_value="—")
            self.demo_pattern.on_update(self._on_demo_pattern)
            self.demo_start = gui.add_dropdown("Demo start", ("—", *demo_files("starts")), initial_value="—")
            self.demo_start.on_update(self._on_demo_start)
            for label, loader in (
                ("Upload robots", session.load_robots),
                ("Upload pattern", session.load_pattern),
                ("Upload trace", session.load_trace),
                ("Upload schedule", session.load_schedule),
            ):
                gui.add_upload_button(label, mime_type="*/*").on_upload(self._uploader(loader))
            for label, name, make in (
                ("Download robots", "robots.json", session.robots_file),
                ("Download pattern", "pattern.json", session.pattern_file),
                ("Download trace", "trace.jsonl", session.trace_file),
                ("Download schedule", "schedule.jsonl", session.schedule_file),
            ):
                gui.add_button(label).on_click(self._downloader(name, make))
            gui.add_button("Save screenshot").on_click(self._screenshot)
            self.record = gui.add_button("Record GIF")
            self.record.on_click(self._on_record)
        with gui.add_folder("Moves over events", expand_by_default=False):
            self.plot = gui.add_uplot(
                (np.array([0.0]), np.array([0.0])),
                ({"label": "event"}, {"label": "moves", "stroke": "#d33", "width": 2}),
                scales={"x": {"time": False}},  # uPlot reads x as timestamps unless told otherwise
                aspect=2.0,
            )

    # ------------------------------------------------------------------ callbacks
    def _guard(self, fn: Callable, title: str = "apf-viz") -> Callable:
        """Run a callback; bad input, or what it has to say (a returned string), is told to the browser
        that caused it, not to every browser (a laptop's hint must not pop up on the projector). Always
        re-render afterwards."""

        def wrapped(event) -> None:
            try:
                said = fn(event)
                if isinstance(said, str) and said:
                    tell(event.client, title, said)
            except (InputError, ValueError) as err:
                tell(event.client, "Refused", str(err), error=True)
            self.changed()

        return wrapped

    def _on_control(self, event) -> None:
        value = event.target.value
        s = self.session
        if value == "Step":
            s.pause()
            if not s.step():
                tell(event.client, "Step", s.why_not_step())
        elif value == "Back":
            s.back()
        elif value in ("Play", "Pause"):
            s.toggle_play()
        elif value == "Reset":
            s.reset()
        self.changed()

    # Values from a browser are checked by the session (a page may send any value over its websocket).
    def _on_numbers(self, event) -> None:
        if event.client is not None:
            self.session.set_numbers(bool(self.numbers.value))
            self.changed()

    def _on_jump(self, event) -> None:
        """Next move / Next stage run the scheduler until something happens (the result goes to the
        browser that asked); Frame run points that browser's camera at the whole run."""
        value, client = event.target.value, event.client
        if value == "Frame run":
            if client is not None:
                self.frame(client)
            return
        what = "move" if value == "Next move" else "stage"
        result = self.session.run_until(what)  # type: ignore[arg-type]
        if client is not None:
            client.add_notification(value, result, auto_close_seconds=5.0)
        self.changed()

    def _set_speed(self, event) -> None:
        if event.client is not None:
            self._guard(lambda e: self.session.set_speed(self.speed.value))(event)

    def _on_timeline(self, event) -> None:
        if event.client is not None:
            self._guard(lambda e: self.session.seek(self.timeline.value))(event)

    def _on_scheduler(self, event) -> None:
        if event.client is not None:
            self._guard(lambda e: self.session.set_scheduler(self.scheduler.value))(event)

    def _on_seed(self, event) -> None:
        if event.client is not None:
            self._guard(lambda e: self.session.set_seed(self.seed.value))(event)

    def _on_algorithm(self, event) -> None:
        if event.client is not None and self.algorithm.value != self.session.algorithm_name:
            self._guard(lambda e: self.session.set_algorithm(self.algorithm.value))(event)

    def _on_semantics(self, event) -> None:
        if event.client is not None and self.semantics.value != self.session.config.light_semantics:
            self._guard(lambda e: self.session.set_light_semantics(self.semantics.value))(event)

    def _algorithm_names(self, current: str | None = None) -> tuple[str, ...]:
        names = [*ALGORITHMS, *(n for n in self.session.run.plugins if ":" not in n)]
        current = current or self.session.algorithm_name
        return tuple(names if current in names else [*names, current])

    def _on_mode(self, event) -> None:
        if event.client is None:
            return
        mode = MODES.get(self.mode.value)
        problem = self.session.set_mode(mode) if mode is not None else f"no mode {self.mode.value!r}"  # type: ignore[arg-type]
        if problem:  # refused: the drafts stay, and the browser that asked is told why
            self.mode.value = MODE_LABELS[self.session.mode]
            tell(event.client, "Still editing", problem, error=True)
        self.changed()

    def _on_all_activations(self, event) -> None:
        if event.client is not None:
            keep = bool(self.all_activations.value)
            if keep != (not self.session.config.skip_noops):
                self._guard(lambda e: self.session.set_all_activations(keep))(event)

    def _on_verify(self, event) -> None:
        why_not = self.verifier.start(self.session.config, self.session.run.plugins)
        if why_not:
            tell(event.client, "Verify", why_not, error=True)
        else:
            self._verify_client = event.client
        self.changed()

    def _verified(self, status: VerifyStatus) -> None:
        """From the verifier's thread: progress, or the end (a counterexample is loaded into the run)."""
        if status.state != "running":
            if status.trace is not None:
                try:
                    self.session.load_trace("counterexample.jsonl", status.trace.encode(), MAX_TRACE_BYTES)
                except InputError as e:  # cannot happen for the engine's own replay; said if it does
                    tell(self._verify_client, "Verify", f"the counterexample did not load: {e}", error=True)
            tell(self._verify_client, "Verify", status.text, error=status.state == "violation")
        self.changed()

    def _on_compare(self, event) -> None:
        if event.target.value == "Compare":
            name = self.compare_with.value.strip()
            if name == self.session.algorithm_name:
                tell(event.client, "Compare", f"the run already uses {name}: name another algorithm", True)
                return
            self._guard(lambda e: self.session.compare_with(name))(event)
        else:
            self._guard(lambda e: self.session.compare_with(None))(event)
        for client in self.server.get_clients().values():
            self.frame(client)  # both runs in view

    def _on_click_mode(self, event) -> None:
        if event.client is not None:
            self.session.set_click_advances(self.click.value == "advance")
            self.changed()

    def _on_demo(self, event) -> None:
        """A ready scenario; what it shows stays under the dropdown, for the room to read."""
        if event.client is None or self.demo.value == "—":
            return

        def load(e) -> None:
            self.session.load_scenario(self.demo.value)

        self._guard(load)(event)

    def _on_demo_pattern(self, event) -> None:
        if event.client is not None and self.demo_pattern.value != "—":
            self._guard(lambda e: self._load_demo("", self.demo_pattern.value, self.session.load_pattern))(
                event
            )

    def _on_demo_start(self, event) -> None:
        if event.client is not None and self.demo_start.value != "—":
            self._guard(lambda e: self._load_demo("starts", self.demo_start.value, self.session.load_robots))(
                event
            )

    @staticmethod
    def _load_demo(folder: str, name: str, load: Callable[[str, bytes], str | None]) -> str | None:
        """A dropdown's value names a file only through the list of demo files: never a path."""
        path = demo_files(folder).get(name)
        if path is None:
            raise InputError(f"no demo called {name[:80]!r}")
        return load(path.name, path.read_bytes())

    def _uploader(self, loader: Callable[[str, bytes], str | None]) -> Callable:
        def on_upload(event) -> None:
            f = event.target.value
            self._guard(lambda e: loader(f.name, f.content), f.name)(event)

        return on_upload

    def _downloader(self, filename: str, make: Callable[[], str]) -> Callable:
        def on_click(event) -> None:
            if event.client is not None:
                event.client.send_file_download(filename, make().encode("utf-8"))

        return on_click

    # ------------------------------------------------------------------ showing a view
    def refresh(self, view: SessionView) -> None:
        s = self.session
        self.controls.options = ("Step", "Back", "Pause" if s.playing else "Play", "Reset")
        self.timeline.max = max(1, view.history_length)
        self.timeline.value = view.steps
        self.event.value = view.event
        last = view.last_events[0] if view.last_events else ""
        if self.last_event.value != last:
            self.last_event.value = last
            latest = f"<small><b>{view.last_events[0]}</b></small>" if view.last_events else ""
            self.log.content = "  \n".join([latest, *(f"<small>{e}</small>" for e in view.last_events[1:6])])
        note = f"<small>{symbol_html(view.scenario_note)}</small>" if view.scenario_note else ""
        if self.demo_note.content != note:
            self.demo_note.content = note
        if not view.scenario_note and self.demo.value != "—":
            self.demo.value = "—"  # another run replaced the scenario
        self.stats.content = (
            f"Algorithm **{view.algorithm}**  \n"
            f"Moves **{view.moves}** · cycles **{view.cycles}** · step {view.steps}/{view.history_length}  \n"
            f"Stage: **{view.stage}** · moves/(k·D) = {view.moves_per_kD:.3f}  \n"
            + (f"Passed over (changing nothing): {view.skipped:,} robot·steps  \n" if view.skipped else "")
            + f"Lights in use: {', '.join(view.lights_in_use)}"
        )
        self.banner.content = self._banner(view)
        following = view.trace_position is not None
        if self.branch.visible != following:
            self.branch.visible = following
        trace = ""
        if following:
            at, of = view.trace_position  # type: ignore[misc]
            end = " — its end" if at >= of else ""
            trace = f"Following {view.following_what}: event **{at}** of {of}{end}"
        if view.trace_note:
            trace += f"  \n<small>The trace: {symbol_html(view.trace_note)}</small>"
        self.trace.content = trace
        aside = view.set_aside is not None
        if self.restore.visible != aside:
            self.restore.visible = aside
        self.aside.content = (
            f"Set aside: the branch you left, {view.set_aside[1]} recorded step(s) after step "
            f"{view.set_aside[0]}."
            if view.set_aside
            else ""
        )
        marks = tuple(GuiSliderMark(float(v), label) for v, label in view.timeline_marks)
        if self.timeline._marks != (marks or None):  # viser has no public setter for marks yet
            self.timeline._marks = marks or None
        self.compare_status.content = self._compare_text(view)
        v = self.verifier.status
        running = v.state == "running"
        self.verify_status.content = (
            f"Verifying… **{v.states:,}** states, frontier {v.frontier:,}, {v.rate:,.0f} states/s"
            if running
            else (f"Verify: {v.text}" if v.text else "")
        )
        if self.cancel_verify.visible != running:
            self.cancel_verify.visible = running
        manual = s.scheduler_name == "manual"
        if self.click.visible != manual:
            self.click.visible = manual
        click = "advance" if view.click_advances else "select"
        if self.click.value != click:
            self.click.value = click
        if self.numbers.value != view.numbers:
            self.numbers.value = view.numbers
        self.caption.content = view.caption
        self.why.content = why_markdown(view)
        if self.algorithm.value != s.algorithm_name:
            self.algorithm.options = self._algorithm_names(s.algorithm_name)
            self.algorithm.value = s.algorithm_name
            self.variant.value = s.algorithm_name  # the field follows the run's algorithm
        if self.all_activations.value == s.config.skip_noops:
            self.all_activations.value = not s.config.skip_noops
        if self.semantics.value != s.config.light_semantics:
            self.semantics.value = s.config.light_semantics
        legend = legend_html(view)  # its overlay rows change with the run (K appears, a frame is fixed)
        if self.legend.content != legend:
            self.legend.content = legend
        self.counts.content = self._counts(view)
        if self.mode.value != MODE_LABELS[view.mode]:
            self.mode.value = MODE_LABELS[view.mode]
        if self.scheduler.value != self._scheduler_label():
            self.scheduler.value = self._scheduler_label()
        self.next_phase.content = self._next_phases(view)
        series = np.array(view.move_series, dtype=np.float64).reshape(-1, 2)  # at most SERIES_POINTS
        self.plot.data = (series[:, 0], series[:, 1])

    def _screenshot(self, event) -> None:
        """The clicking browser's view as it is now, as a PNG download named after the event shown."""
        client = event.client
        if client is None:
            return
        name = f"apf-viz-event-{self.session.view().event}.png"
        try:
            rgba = render_view(client, "png")
        except (TimeoutError, RuntimeError) as err:  # viser's errors for no frame / a lost browser
            client.add_notification("Screenshot failed", str(err), color="red", auto_close_seconds=8.0)
            return
        client.send_file_download(name, png_on_white(rgba))

    def _on_record(self, event) -> None:
        """Record GIF / Stop recording: one recording at a time, of the browser that started it."""
        client = event.client
        if client is None:
            return
        with self._recording_lock:
            if self._recorder is not None:
                self._recorder.stop()
                return
            first = self.session.view().event
            self._recorder = GifRecorder(client, lambda gif, why: self._recorded(client, first, gif, why))
            self.record.label = "Stop recording"
        client.add_notification(
            "Recording a GIF",
            f"of this view, up to {RECORD_FPS:g} frames a second for at most {MAX_SECONDS:g} s",
            auto_close_seconds=4.0,
        )

    def _recorded(self, client, first: int, gif: bytes | None, why: str) -> None:
        with self._recording_lock:
            self._recorder = None
            self.record.label = "Record GIF"
        if gif is None:
            client.add_notification("Recording failed", why, color="red", auto_close_seconds=8.0)
            return
        client.send_file_download(f"apf-viz-events-{first}-{self.session.view().event}.gif", gif)
        if why:  # stopped early: the browser stopped answering
            client.add_notification("Recording stopped", why, color="red", auto_close_seconds=8.0)

    @staticmethod
    def _compare_text(view: SessionView) -> str:
        other = view.compare
        if other is None:
            return ""

        def side(name: str, v: SessionView) -> str:
            state = (v.outcome or "running").upper()
            return f"{name} **{v.algorithm}**: {state}, event {v.event}, {v.moves} moves"

        if view.divergence is None:
            split = "Same configurations so far."
        else:
            at, what = view.divergence
            split = f"First divergence at event **{at}**: A {what.split(' | ')[0]}; B {what.split(' | ')[1]}"
        return f"{side('A', view)}  \n{side('B', other)}  \n{split}"

    def _scheduler_label(self) -> str:
        return next(k for k, v in SCHEDULER_LABELS.items() if v == self.session.scheduler_name)

    @staticmethod
    def _banner(view: SessionView) -> str:
        if view.outcome is None:
            return ""
        icon = {"formed": "✅", "collision": "💥", "stuck": "⛔", "limit": "⏱"}.get(view.outcome, "")
        detail = f"\n\n{view.collision[0]} (red on the grid)" if view.collision else ""
        if view.never_act:
            detail = "\n\nNo next cycle of any robot changes anything: all (ringed dark red) will never act"
        if view.outcome == "formed":
            detail = "\n\nEvery robot is on a target cell of the pattern."
        return f"## {icon} {view.outcome.upper()}{detail}"

    @staticmethod
    def _counts(view: SessionView) -> str:
        if view.mode == "edit-pattern":
            return f"Targets: **{view.draft_count}** / {view.robot_count} robots — click cells to toggle"
        if view.mode == "edit-robots":
            axis = f"  \n⚠ symmetric about y = {view.axis:g}: unsolvable" if view.axis is not None else ""
            return f"Robots: **{view.robot_count}** — click: add, flip y, remove{axis}"
        return f"Pattern: {view.draft_count} points for {len(view.robots)} robots"

    def _next_phases(self, view: SessionView) -> str:
        if self.session.scheduler_name != "manual":
            return ""
        counts: dict[str, list[int]] = {}
        for i, r in enumerate(view.robots):
            counts.setdefault(r.next_event, []).append(i)
        parts = [
            f"{phase}: {', '.join(map(str, rs[:20]))}{'…' if len(rs) > 20 else ''}"
            for phase, rs in sorted(counts.items())
        ]
        head = (
            "Manual — click a robot to run its next phase."
            if view.click_advances
            else "Manual, Click: select — a click only selects; Step runs the selected robot's next phase."
        )
        return head + "  \n" + "  \n".join(parts)
