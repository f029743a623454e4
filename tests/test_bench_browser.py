"""The adversary's bench and the studio in a real browser (Chromium), as their users work: branches kept
and re-entered from the History folder, and what the studio saves being what the page shows."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from apf_viz.ui.app import App, demo_session, free_port
from tests.test_ui_browser import open_page, shot, wait_for

pytest.importorskip("playwright.sync_api")


@pytest.fixture
def app() -> Iterator[App]:
    a = App(demo_session(), port=free_port(), verbose=False)
    yield a
    a.stop()


def _click_steps(page, app: App, n: int) -> None:
    step = page.get_by_role("button", name="Step", exact=True)
    for _ in range(n):
        before = app.session.engine.step_index
        step.click()
        wait_for(lambda before=before: app.session.engine.step_index == before + 1)


def _enter(page, app: App, starts: str) -> None:
    """Pick the branch whose label says ``starts`` in the Branches list, and Enter branch."""
    page.get_by_role("combobox", name="Branches").click()
    page.get_by_role("option").filter(has_text=starts).first.click()
    page.get_by_role("button", name="Enter branch").click()
    wait_for(lambda: app.session.run.following_what.startswith("branch #"))


def test_branch_return_branch_again_and_both_branches_are_re_entered(browser, app):
    s = app.session
    s.set_scheduler("async")
    s.set_seed(3)
    for _ in range(40):
        s.step()
    trunk = s.engine.history.events()
    page = open_page(browser, app, {"width": 1024, "height": 768})
    s.seek(20)
    s.set_scheduler("round-robin")
    app.request_render()
    _click_steps(page, app, 8)  # a different adversary from step 20: the first branch
    first = s.engine.history.events()
    page.get_by_role("button", name="Return to set-aside branch").click()
    wait_for(lambda: s.run.following)
    while s.step():  # follow the trunk back to its end
        pass
    assert s.engine.history.events() == trunk
    s.seek(30)
    app.request_render()
    page.get_by_role("button", name="Branch here").click()
    wait_for(lambda: not s.run.following)
    s.set_scheduler("fsync")
    _click_steps(page, app, 5)  # the second branch, at step 30
    page.get_by_text("Branches kept: 2").wait_for()
    labels = s.view().branches
    assert len(labels) == 2 and "left at step 30" in labels[1] and "left at step 30" not in labels[0]
    _enter(page, app, labels[0].split(",")[0])  # the first branch (it left at step 20 or just after)
    while s.step():
        pass
    assert s.engine.history.events() == first  # the step-20 branch, exactly
    _enter(page, app, "left at step 30")
    while s.step():
        pass
    assert s.engine.history.events() == trunk  # the trunk's rest, exactly
    app.request_render()
    page.get_by_text("Branches kept: 2").wait_for()  # entering keeps the line left: none is lost
    shot(page, "branches-1024")
    page.close()
