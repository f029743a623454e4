"""A run's moment as figure text, and the paper's figures (``demo_patterns/figures.json``) exported."""

from __future__ import annotations

import re
from pathlib import Path

from apf_viz.core.files import write_atomic
from apf_viz.core.formats import InputError
from apf_viz.figure.drawing import drawing_of
from apf_viz.figure.svg import to_svg
from apf_viz.figure.tikz import to_tikz
from apf_viz.lecture import Marked
from apf_viz.workbench.session import Session
from apf_viz.workbench.view_model import SessionView

WRITERS = {"svg": to_svg, "tikz": to_tikz}
SUFFIXES = {"svg": ".svg", "tikz": ".tex"}


def figure_text(
    session: Session, fmt: str, select: int | None = None, caption: str = "", marked: Marked | None = None
) -> str:
    """The figure of the session's run as it is now (``select``: whose rays and hidden robots;
    ``marked``: the robot a paper's caption names)."""
    session.selected = select
    return figure_of(session.view(), fmt, caption, marked)


def figure_png(
    session: Session, select: int | None = None, caption: str = "", marked: Marked | None = None
) -> bytes:
    """The figure as a PNG (matplotlib: the ``sweep`` extra)."""
    from apf_viz.figure.png import to_png

    session.selected = select
    return to_png(drawing_of(session.view(), caption, marked))


def figure_of(view: SessionView, fmt: str, caption: str = "", marked: Marked | None = None) -> str:
    """The figure of what a page shows (its selection's rays and hidden robots included)."""
    if fmt not in WRITERS:
        raise InputError(f"figure format {fmt!r}: choose {' or '.join(WRITERS)}")
    return WRITERS[fmt](drawing_of(view, caption, marked))


def figure_zip(view: SessionView, caption: str) -> tuple[str, bytes]:
    """Save figure: the page's view as SVG and TikZ in one zip, named after the event shown."""
    import io
    import zipfile

    stem = f"apf-viz-event-{view.event}"
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as z:
        for fmt, suffix in SUFFIXES.items():
            z.writestr(stem + suffix, figure_of(view, fmt, caption))
    return stem + ".zip", buffer.getvalue()


def run_to_event(session: Session, event: int | None) -> None:
    """Step the run until ``event`` events have happened (None: a loaded trace's end), or it ends."""
    if event is None:
        while session.step():
            pass
        return
    if event < 0:
        raise InputError(f"--event {event}: a number of events, 0 or more")
    while session.engine.state.events < event and session.step():
        pass
    if session.engine.state.events < event:
        raise InputError(f"--event {event}: the run ends after {session.engine.state.events} events")


def figure_session(label: str) -> tuple[Session, str]:
    """The paper's figure ``label`` reached as its one-stop lecture reaches it, and its caption."""
    from apf_viz.lecture import figures
    from apf_viz.workbench.session.demo import demo_session

    figure = figures().get(label)
    if figure is None:
        raise InputError(f"--figure {label!r}: the figures are {', '.join(figures())}")
    session = demo_session()
    session.start_lecture(figure.as_lecture())
    session.lecturer = None  # the figure alone: no lecture's words in it
    return session, f"Figure “{label}”: {figure.caption}"


def figure_file_stem(label: str) -> str:
    """A figure's file name, without spaces (a shell, a LaTeX \\input and a URL take it as it is)."""
    return "figure-" + re.sub(r"[^A-Za-z0-9_.-]+", "-", label).strip("-")


def paper_figures(folder: Path, caption: bool = False) -> list[Path]:
    """Every figure of figures.json, as SVG and TikZ, into ``folder`` (``figure-LABEL.svg``, ``.tex``),
    each robot its caption names marked; the caption itself only if asked (a paper sets its own)."""
    from apf_viz.lecture import figures

    if folder.exists() and not folder.is_dir():
        raise InputError(f"--all-figures {folder}: not a folder")
    folder.mkdir(parents=True, exist_ok=True)
    written = []
    for label, figure in figures().items():
        session, words = figure_session(label)
        for fmt, suffix in SUFFIXES.items():
            path = folder / f"{figure_file_stem(label)}{suffix}"
            text = figure_text(session, fmt, None, words if caption else "", figure.marked)
            write_atomic(path, text, through_links=False)
            written.append(path)
    return written
