"""A lecture exported for the notes: every stop rendered in the browser that asked, as a slide (the
picture, its legend, the stop's words under it) in a zip with an HTML page of the words beside each
picture. Runs in its own thread: each stop is reached, drawn, then read back from the browser."""

from __future__ import annotations

import html
import io
import threading
import time
import zipfile
from collections.abc import Callable

from apf_viz.ui.image import png_on_white
from apf_viz.ui.recorder import render_view
from apf_viz.ui.slide import compose
from apf_viz.workbench.screen_state import BrowserState
from apf_viz.workbench.session import Session
from apf_viz.workbench.view_model.legend import plain, slide_legend

SETTLE_SECONDS = 0.8  # after a stop is reached, for the frame (and a framed camera) to reach the browser


def slide_words(where: str, title: str, say: str, stage: str) -> list[str]:
    return [f"{plain(title)} ({where})", plain(say), plain(stage)]


def index_html(title: str, stops: list[tuple[str, str, str]]) -> str:
    """The lecture as one page: each stop's picture with its title and words, for the notes."""
    body = "".join(
        f'<section><h2>{html.escape(t)}</h2><img src="{html.escape(png)}" style="max-width:100%">'
        f"<p>{html.escape(say)}</p></section>"
        for png, t, say in stops
    )
    return (
        f'<!doctype html><meta charset="utf-8"><title>{html.escape(title)}</title>'
        f"<h1>{html.escape(title)}</h1>{body}"
    )


class LectureExport:
    """Exports the session's lecture as seen by ``client``; ``done`` gets the zip (None and why, if not)."""

    def __init__(
        self,
        session: Session,
        client,
        state: BrowserState,
        changed: Callable[[], None],
        done: Callable[[bytes | None, str], None],
    ) -> None:
        self.session, self.client, self.state, self.changed, self.done = (
            session,
            client,
            state,
            changed,
            done,
        )
        self._thread = threading.Thread(target=self._run, name="apf-viz-lecture-export", daemon=True)
        self._thread.start()

    def _run(self) -> None:
        lecturer = self.session.lecturer
        if lecturer is None:
            self.done(None, "no lecture is loaded")
            return
        lecture, here = lecturer.lecture, lecturer.position
        buffer, pages = io.BytesIO(), []
        try:
            with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as z:
                for i, stop in enumerate(lecture.stops):
                    lecturer.go(i)
                    self.changed()
                    time.sleep(SETTLE_SECONDS)
                    view = self.session.view(self.state)
                    where = f"stop {i + 1} of {len(lecture.stops)}"
                    picture = compose(
                        render_view(self.client, "png"),
                        slide_words(where, stop.title, stop.say, view.stage_line),
                        slide_legend(view),
                    )
                    name = f"stop-{i + 1:02d}.png"
                    z.writestr(name, png_on_white(picture))
                    pages.append((name, f"{i + 1}. {plain(stop.title)}", plain(stop.say)))
                z.writestr("index.html", index_html(lecture.title, pages))
        except (TimeoutError, RuntimeError) as err:  # the browser stopped answering
            self.done(None, str(err))
            return
        finally:
            if here >= 0:
                lecturer.go(here)  # back where the lecture stood
                self.changed()
        self.done(buffer.getvalue(), "")
