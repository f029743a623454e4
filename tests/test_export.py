"""apf-viz export: a lecture or a run as one HTML page with viser's client and the recorded scene."""

from __future__ import annotations

import base64

import pytest

from apf_viz.cli import main
from apf_viz.lecture import lectures
from apf_viz.ui.app import demo_session
from apf_viz.ui.page_export import export_lecture, export_run


def _embedded(html: str) -> bytes:
    start = html.index('window.__VISER_EMBED_DATA__="') + len('window.__VISER_EMBED_DATA__="')
    return base64.b64decode(html[start : html.index('"', start)])


def test_a_lecture_page_holds_every_stop_and_its_words():
    lecture = lectures()["The algorithm in 12 stops"]
    exported = export_lecture(demo_session(), lecture)
    asked = sum(stop.ask is not None for stop in lecture.stops)  # a question adds its reveal's frame
    assert asked == 1 and exported.frames == len(lecture.stops) + asked and exported.events == 542
    assert len(exported.html.encode()) <= 15_000_000
    assert len(_embedded(exported.html)) > 1000 and "<script" in exported.html


def test_a_run_page_keeps_every_move_and_says_it_is_thinned():
    session = demo_session()
    exported = export_run(session, "the heart")
    assert session.engine.outcome == "formed"
    # every step that moved a robot or changed a light is a frame: at least one per move
    assert exported.frames >= session.view().moves
    assert exported.frames < session.engine.step_index  # Looks that change nothing are merged


def test_the_command_writes_the_page_and_refuses_bad_input_in_one_line(tmp_path, capsys):
    out = tmp_path / "lecture.html"
    assert main(["export", "--lecture", "algorithm-in-12-stops", "--out", str(out)]) == 0
    assert out.stat().st_size > 100_000 and "12 stops" in capsys.readouterr().out
    for argv, message in (
        (["--lecture", "no-such-lecture"], "no-such-lecture"),
        (["--trace", str(tmp_path / "missing.jsonl")], "missing.jsonl"),
        ([], "give --lecture NAME"),
    ):
        bad = tmp_path / "bad.html"
        with pytest.raises(SystemExit) as ended:
            main(["export", *argv, "--out", str(bad)])
        assert ended.value.code == 2 and message in capsys.readouterr().err and not bad.exists()
