"""Files: demo patterns and starts, uploads (robots, pattern, trace, schedule), downloads of the current
files, and this browser's view as a PNG or a GIF. Downloads are saved at once (the browser's own download),
so no notification with a link is left over the canvas."""

from __future__ import annotations

import threading
from collections.abc import Callable

from apf_viz.core.files import read_bytes
from apf_viz.core.formats import MAX_TRACE_BYTES, InputError
from apf_viz.demos import demo_files
from apf_viz.ui.image import png_on_white
from apf_viz.ui.lecture_export import LectureExport
from apf_viz.ui.page_export import export_run
from apf_viz.ui.panels.context import PanelContext, tell
from apf_viz.ui.recorder import MAX_SECONDS, RECORD_FPS, GifRecorder, render_view
from apf_viz.ui.slide import compose
from apf_viz.workbench.view_model import SessionView
from apf_viz.workbench.view_model.legend import slide_caption, slide_legend


def load_demo(folder: str, name: str, load: Callable[[str, bytes], str | None]) -> str | None:
    """A dropdown's value names a file only through the list of demo files: never a path."""
    path = demo_files(folder).get(name)
    if path is None:
        raise InputError(f"no demo called {name[:80]!r}")
    return load(path.name, read_bytes(path, MAX_TRACE_BYTES))


class FilesFolder:
    def __init__(self, gui, ctx: PanelContext) -> None:
        self.ctx = ctx
        self.recorder: GifRecorder | None = None  # this browser's recording, if one runs
        self._recording_lock = threading.Lock()
        s = ctx.session
        with gui.add_folder("Files", expand_by_default=False):
            self.demo_pattern = ctx.driving(
                gui.add_dropdown("Demo pattern", ("—", *demo_files()), initial_value="—"), shared=True
            )
            self.demo_pattern.on_update(
                ctx.from_browser(lambda e: self._demo("", self.demo_pattern.value, s.load_pattern))
            )
            self.demo_start = ctx.driving(
                gui.add_dropdown("Demo start", ("—", *demo_files("starts")), initial_value="—"), shared=True
            )
            self.demo_start.on_update(
                ctx.from_browser(lambda e: self._demo("starts", self.demo_start.value, s.load_robots))
            )
            # Commands by name, looked up when used: the page may be attached to another run by then.
            for label, loader in (
                ("Upload robots", "load_robots"),
                ("Upload pattern", "load_pattern"),
                ("Upload trace", "load_trace"),
                ("Upload schedule", "load_schedule"),
                ("Upload lecture", "load_lecture"),
            ):
                button = ctx.driving(gui.add_upload_button(label, mime_type="*/*"), shared=True)
                button.on_upload(self._uploader(loader))
            for label, name, make in (
                ("Download robots", "robots.json", "robots_file"),
                ("Download pattern", "pattern_file_name", "pattern_file"),
                ("Download trace", "trace.jsonl", "trace_file"),
                ("Download schedule", "schedule.jsonl", "schedule_file"),
            ):
                gui.add_button(label).on_click(self._downloader(name, make))
            self._picture_controls(gui)
        self.exporting: LectureExport | None = None

    def _picture_controls(self, gui) -> None:
        """What this page shows, taken away: a screenshot, a GIF, a figure, the run as a page, the lecture."""
        ctx = self.ctx
        gui.add_button("Save screenshot").on_click(self._screenshot)
        self.explained = gui.add_checkbox(
            "With legend, caption",
            initial_value=True,
            hint="the screenshot gets the legend of what it shows beside it and the stage, last event "
            "and outcome under it, for a slide",
        )
        self.record = gui.add_button("Record GIF")
        self.record.on_click(self._on_record)
        gui.add_button(
            "Export page",
            hint="the run so far as one HTML page that plays from disk, with no server (every move kept)",
        ).on_click(ctx.guard(self._export_page, "Export page", mine=True))
        gui.add_button(
            "Save figure",
            hint="what this page shows, for a paper: SVG and TikZ (grid units, a legend) in a zip",
        ).on_click(ctx.guard(self._figure, "Save figure", mine=True))
        ctx.driving(
            gui.add_button(
                "Export lecture",
                hint="every stop of the lecture being followed as a slide (PNG, legend, its words) and "
                "an HTML page of them, in one zip; keep your hands off the run meanwhile",
            ),
            shared=True,
        ).on_click(self._on_export)

    @staticmethod
    def _demo(folder: str, name: str, load: Callable[[str, bytes], str | None]) -> str | None:
        return load_demo(folder, name, load) if name != "—" else None

    def _uploader(self, loader: str) -> Callable:
        def on_upload(event) -> None:
            f = event.target.value
            self.ctx.guard(lambda e: getattr(self.ctx.session, loader)(f.name, f.content), f.name)(event)

        return on_upload

    def _downloader(self, filename: str, make: str) -> Callable:
        """A download of ``make()``'s text, saved as ``filename`` (or, naming a method, what it says)."""

        def on_click(event) -> None:
            if event.client is not None:
                text = getattr(self.ctx.session, make)()
                named = getattr(self.ctx.session, filename, None)
                name = named() if callable(named) else filename
                event.client.send_file_download(name, text.encode("utf-8"), save_immediately=True)

        return on_click

    def _event(self) -> int:
        return self.ctx.session.engine.state.events

    def _export_page(self, event) -> str:
        """The run this page shows, from its start to where it is, recorded on a copy (the run itself,
        shared or not, does not move)."""
        from apf_viz.workbench.session.branch import branch

        if event.client is None:
            return ""
        copy = branch(self.ctx.session)
        view = self.ctx.view()
        if copy.engine.step_index == 0:
            return "nothing to export yet: step or play the run first"
        exported = export_run(copy, f"{view.algorithm_title or view.algorithm}, {view.scheduler}")
        name = f"apf-viz-run-event-{view.event}.html"
        event.client.send_file_download(name, exported.html.encode(), save_immediately=True)
        return f"{name}: {exported.frames} frames of the run to event {view.event}; it plays from disk"

    def _figure(self, event) -> str:
        from apf_viz.figure.export import figure_zip

        if event.client is None:
            return ""
        view = self.ctx.view()
        stage = f" — {view.stage}" if view.stage else ""
        name, data = figure_zip(view, f"{view.algorithm_title or view.algorithm}, event {view.event}{stage}")
        event.client.send_file_download(name, data, save_immediately=True)
        return f"{name}: the figure as SVG and TikZ"

    def _screenshot(self, event) -> None:
        """The clicking browser's view as it is now, at its canvas's resolution (collapse the panel for the
        whole window), as a PNG named after the event shown; with the legend and caption if asked."""
        client = event.client
        if client is None:
            return
        name = f"apf-viz-event-{self._event()}.png"
        try:
            rgba = render_view(client, "png")
        except (TimeoutError, RuntimeError) as err:  # viser's errors for no frame / a lost browser
            client.add_notification("Screenshot failed", str(err), color="red", auto_close_seconds=8.0)
            return
        if self.explained.value:
            view = self.ctx.view()
            rgba = compose(rgba, slide_caption(view), slide_legend(view))
        client.send_file_download(name, png_on_white(rgba), save_immediately=True)

    def _on_record(self, event) -> None:
        """Record GIF / Stop recording: one recording at a time, of this browser's view."""
        client = event.client
        if client is None:
            return
        with self._recording_lock:
            if self.recorder is not None:
                self.recorder.stop()
                return
            first = self._event()
            self.recorder = GifRecorder(client, lambda gif, why: self._recorded(client, first, gif, why))
            self.record.label = "Stop recording"
        client.add_notification(
            "Recording a GIF",
            f"of this view, up to {RECORD_FPS:g} frames a second for at most {MAX_SECONDS:g} s",
            auto_close_seconds=4.0,
        )

    def _recorded(self, client, first: int, gif: bytes | None, why: str) -> None:
        with self._recording_lock:
            self.recorder = None
            self.record.label = "Record GIF"
        if gif is None:
            client.add_notification("Recording failed", why, color="red", auto_close_seconds=8.0)
            return
        client.send_file_download(f"apf-viz-events-{first}-{self._event()}.gif", gif, save_immediately=True)
        if why:  # stopped early: the browser stopped answering
            client.add_notification("Recording stopped", why, color="red", auto_close_seconds=8.0)

    def _on_export(self, event) -> None:
        client = event.client
        if client is None or not self.ctx.may(event):  # it steps the shared run through the stops
            return
        if self.ctx.session.lecturer is None:
            tell(client, "Export lecture", "pick a Lecture (Run) or upload one first", error=True)
            return
        if self.exporting is not None:
            tell(client, "Export lecture", "an export is running: wait for its zip")
            return
        n = len(self.ctx.session.lecturer.lecture.stops)
        tell(client, "Export lecture", f"{n} stops: each is reached and drawn, about a second each")
        self.exporting = LectureExport(
            self.ctx.session,
            client,
            self.ctx.state,
            self.ctx.changed,
            lambda z, why: self._exported(client, z, why),
        )

    def _exported(self, client, archive: bytes | None, why: str) -> None:
        self.exporting = None
        if archive is None:
            tell(client, "Export lecture failed", why, error=True)
            return
        client.send_file_download("lecture.zip", archive, save_immediately=True)

    def refresh(self, view: SessionView) -> None:
        pass  # nothing here follows the run
