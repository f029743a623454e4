"""The room at a glance in a real browser (Chromium, 1024×768): the presenter's Room folder lists the
class pages by laptop number, what each does, and puts one laptop's own run beside the shared run on the
projector, anonymised, and takes it down; it hands the shared run to one laptop and takes it back."""

from __future__ import annotations

import pytest

from apf_viz.ui.app import App
from tests.test_question_browser import PROJECTOR, class_page
from tests.test_ui_browser import _choose, open_folder, open_page, shot, wait_for

pytest.importorskip("playwright.sync_api")
pytestmark = pytest.mark.browser


@pytest.fixture
def app(demo_app: App) -> App:
    return demo_app


def titles(renderer) -> list[str]:
    return [h.text for n, h in renderer.nodes().items() if n.startswith("/title/") and h.visible]


def test_the_room_lists_the_laptops_shows_one_beside_and_hands_the_run_to_another(browser, app):
    projector = open_page(browser, app, PROJECTOR)
    follower, trier = class_page(browser, app), class_page(browser, app)
    trier.get_by_role("button", name="Try it yourself").click()
    trier.get_by_text("Your own run").first.wait_for()
    for _ in range(6):
        trier.keyboard.press("Enter")
    (own,) = [x for x in app.screens.values() if x.own is not None]
    wait_for(lambda: own.session.engine.state.events == 6)
    assert app.session.engine.state.events == 0  # the projector's run is untouched

    open_folder(projector, "Room")
    listing = projector.get_by_text("2 class page(s), 1 trying a run of their own")
    listing.wait_for()
    projector.get_by_text("laptop 1: follows the lecture").wait_for()
    listed = "laptop 2: its own run, event 6, running"
    try:
        projector.get_by_text(listed).wait_for()
    except Exception as err:  # say what the Room lists instead (it failed once, under the suite's load)
        room = [page.words() for page in app.classroom.listing()]
        body = projector.inner_text("body")[:1500]
        raise AssertionError(f"no “{listed}”; the room has {room}; the page: {body}") from err
    # Each laptop shows its own number, as the Room lists it: "laptop 1, your hand" is answerable.
    follower.get_by_text("laptop 1").first.wait_for()
    trier.get_by_text("laptop 2").first.wait_for()
    follower.keyboard.press("p")  # in presentation mode, first on its caption's top line
    follower.locator("[data-apf=words]").filter(has_text="laptop 1 ·").wait_for()
    follower.keyboard.press("p")

    _choose(projector, "Laptop", "laptop 2")
    projector.get_by_role("button", name="Show its run beside").click()
    # anonymised: a number, no name or address
    wait_for(
        lambda: app.pair.second is not None and titles(app.pair.second) == ["laptop 2 · event 6 · running"]
    )
    assert titles(app.renderer) == ["the lecture's run · running"]
    projector.get_by_text("laptop 2: its own run, event 6, running (beside)").wait_for()
    shot(projector, "room-beside-1024")
    trier.keyboard.press("Enter")  # the laptop goes on: the projector follows it
    wait_for(
        lambda: app.pair.second is not None and titles(app.pair.second) == ["laptop 2 · event 7 · running"]
    )
    projector.get_by_role("button", name="Take it down").click()
    wait_for(lambda: app.pair.second is None)

    follower.keyboard.press("Enter")  # not handed the run: refused
    follower.get_by_text("Following the lecture").first.wait_for()
    assert app.session.engine.state.events == 0
    _choose(projector, "Laptop", "laptop 1")
    projector.get_by_role("button", name="Hand it the run").click()
    projector.get_by_text("laptop 1: follows the lecture (drives)").wait_for()
    follower.get_by_role("button", name="Step").wait_for()  # its driving controls appear
    follower.keyboard.press("Enter")
    wait_for(lambda: app.session.engine.state.events == 1)
    projector.get_by_role("button", name="Take the run back").click()
    wait_for(lambda: app.classroom.driver is None)
    follower.keyboard.press("Enter")
    follower.wait_for_timeout(500)
    assert app.session.engine.state.events == 1
    for page in (follower, trier, projector):
        page.close()
