"""The worst found (issue #59) in a real browser (Chromium, 1024×768): the schedule `apf-viz adversary`
writes for the Demo heart, loaded from the Adversary panel and played to FORMED, with what the search
says of it and the run's moves/(k·D) on screen, equal to what the search found."""

from __future__ import annotations

import json

import pytest

from apf_viz.cli import main
from apf_viz.core.budget import paper_D
from apf_viz.ui.app import App
from tests.test_ui_browser import open_page, shot, wait_for

pytest.importorskip("playwright.sync_api")
pytestmark = pytest.mark.browser


@pytest.fixture
def app(demo_app: App) -> App:
    return demo_app


def test_the_worst_found_for_the_heart_plays_from_the_adversary_panel(browser, app, tmp_path, capsys):
    found_file = tmp_path / "heart-worst-found.jsonl"
    assert main(["adversary", "--robots", "demo-10", "--pattern", "heart", "--maximize", "moves",
                 "--budget", "10", "--schedule-out", str(found_file), "--json"]) == 0  # fmt: skip
    said = json.loads(capsys.readouterr().out.strip().splitlines()[-1])
    page = open_page(browser, app, {"width": 1024, "height": 768})
    # the Adversary folder is open from the start
    with page.expect_file_chooser() as chooser:
        page.get_by_role("button", name="Load the worst found").click()
    chooser.value.set_files(str(found_file))
    words = f"The worst found by apf-viz adversary: {said['found']:,} moves"
    page.get_by_text(words).first.wait_for()
    page.keyboard.press("Escape")
    app.session.set_speed(1_000)  # the Speed slider's top: the run, not the test, is what is watched
    page.keyboard.press("Space")  # Play: the schedule to its end
    wait_for(lambda: app.session.engine.outcome == "formed", timeout=120)
    e = app.session.engine
    per_kd = e.state.moves / (e.k * paper_D(e.start, e.pattern))
    assert e.state.moves == said["found"] and round(per_kd, 4) == said["per_kD"]
    page.get_by_text(f"moves/(k·D) = {per_kd:.3f}").first.wait_for()
    page.get_by_text("FORMED at event").first.wait_for()
    shot(page, "worst-found-1024")
    page.close()
