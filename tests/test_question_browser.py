"""A lecture stop's question in a real browser (Chromium, 1024×768): three class pages answer, two right
and one wrong, the projector's spread reads 2–1, no class page is sent another's answer, and the reveal
plays the run to the answer."""

from __future__ import annotations

import json
import re
import time
from collections.abc import Iterator

import pytest

from apf_viz.ui.app import App, demo_session, free_port
from tests.test_ui_browser import drawn_there, open_page, screen_of, shot, wait_for

pytest.importorskip("playwright.sync_api")
pytestmark = pytest.mark.browser
PROJECTOR = {"width": 1024, "height": 768}
LECTURE = {
    "format": "apf-viz-lecture",
    "version": 1,
    "title": "Who moves?",
    "stops": [
        {"title": "Ten robots", "scenario": "Heart from 10 robots", "say": "Every light off.",
         "ask": {"kind": "robot"}},
        {"title": "Later", "until": {"event": 20}, "say": "On."},
    ],
}  # fmt: skip


@pytest.fixture
def app() -> Iterator[App]:
    # Several class pages from this one machine, each a laptop of its own (a hall behind one router).
    a = App(demo_session(), port=free_port(), verbose=False, seats_per_address=8)
    a.session.load_lecture("who.json", json.dumps(LECTURE).encode())
    yield a
    a.stop()


def class_page(browser, app: App):
    from playwright.sync_api import Error as PlaywrightError

    before = set(app.screens)
    page = browser.new_page(viewport=PROJECTOR)
    page.set_default_timeout(60_000)
    page.goto(app.addresses[1])
    seat = re.compile(r"\?websocket=ws://[^/]+/seat/[0-9a-f]{16}-[0-9a-f]{16}$")  # to its seat (ui/seat.py)
    for _ in range(3):  # the page's own move to its seat aborts the load being waited on: wait again
        try:
            page.wait_for_url(seat)
            break
        except PlaywrightError:
            if seat.search(page.url):
                break
    assert seat.search(page.url), page.url  # at its seat, whichever wait saw it arrive
    page.get_by_label("Event").wait_for()
    wait_for(lambda: set(app.screens) - before)
    drawn_there(app, page)
    return page


def within_the_caption(page, timeout: float = 10.0) -> None:
    """At 1024×768 the bars (their counts and names) and the stop's state line below them are on screen,
    inside the caption: nothing cut, no scrollbar (found: 243 px of words in a 215 px box). Read until it
    holds or ``timeout`` s have passed: the caption is laid out anew as its words change, and a loaded
    machine was once read a frame before the last line settled (1 px past the bottom)."""
    end = time.time() + timeout
    while True:
        try:
            _within_the_caption(page)
            return
        except AssertionError:
            if time.time() > end:
                raise
            time.sleep(0.5)


def _within_the_caption(page) -> None:
    height = page.viewport_size["height"]
    status = page.locator("[data-apf=status]").last
    status.wait_for()
    box = status.bounding_box()
    assert box is not None and box["y"] + box["height"] <= height, box
    for bar in page.locator("[data-apf=bar]").all():
        b = bar.bounding_box()
        assert b is not None and b["y"] + b["height"] <= box["y"], b  # above the state line, whole
    scrolled = page.locator("[data-apf=words]").last.evaluate(  # its own scroll box: the nearest
        "e => { for (let n = e.parentElement; n; n = n.parentElement) { if (/(auto|scroll)/.test("
        "getComputedStyle(n).overflowY)) return Math.max(0, n.scrollHeight - n.clientHeight - 1); }"
        " return 0; }"
    )
    assert scrolled == 0, f"the caption scrolls by {scrolled} px"


def test_three_class_pages_answer_the_projector_shows_two_to_one_and_the_reveal_plays_to_it(browser, app):
    poll = app.session.screen.poll
    assert poll is not None and poll.answer.right == {"1"}  # the run: robot 1 moves first
    projector = open_page(browser, app, PROJECTOR)
    robot0 = screen_of(app, projector, tuple(map(int, app.session.engine.positions[0])))
    pages = [class_page(browser, app) for _ in range(3)]
    for page in pages[:2]:
        page.get_by_text("Which robot moves next?").first.wait_for()
        page.get_by_role("button", name="robot 1", exact=True).click()  # one tap
    pages[2].mouse.click(*robot0)  # the third answers by a click on robot 0, the canvas as the projector's
    wait_for(lambda: poll.count == 3)
    keys = [app.seat_of(cid) for cid in app.screens]
    assert sorted(poll.given(k) for k in keys if poll.given(k)) == ["0", "1", "1"]
    assert sum(k is not None and k.startswith("seat ") for k in keys) == 3  # each class page has a seat
    pages[2].locator("p").filter(has_text="Your answer: robot 0").wait_for()  # the Question folder
    seat = pages[0].url
    pages[0].reload()  # a page that reloads keeps its seat, and its answer
    pages[0].get_by_label("Event").wait_for()
    assert pages[0].url == seat
    pages[0].locator("p").filter(has_text="Your answer: robot 1").wait_for()
    wait_for(lambda: len(app.screens) == 4)
    assert poll.count == 3
    pages[0].keyboard.press("p")  # a student in presentation mode: the caption says the answer kept
    pages[0].locator("[data-apf=mine]").filter(has_text="Your answer: robot 1").wait_for()
    pages[0].keyboard.press("p")  # the panel back
    pages[1].keyboard.press("p")  # another student follows the reveal in presentation mode

    projector.keyboard.press("p")  # presentation mode: the caption on the canvas
    projector.locator("[data-apf=answered]").filter(has_text="3 of 3 answered").wait_for()  # seats here
    projector.keyboard.press("b")  # the room's answers
    bars = projector.locator("[data-apf=bar]")
    bars.first.wait_for()
    spread = {b.get_attribute("data-choice"): int(b.get_attribute("data-count")) for b in bars.all()}
    assert spread["1"] == 2 and spread["0"] == 1 and sum(spread.values()) == 3
    shot(projector, "question-spread-1024")
    within_the_caption(projector)
    for page in pages:  # a class page is never sent the others' answers
        drawn_there(app, page)
        assert page.locator("[data-apf=bar]").count() == 0 and "answered" not in page.inner_text("body")

    projector.keyboard.press("r")  # the reveal plays the run to the answer
    wait_for(lambda: app.session.engine.step_index == poll.answer.step and not app.session.playing)
    projector.get_by_text("The run's answer: robot 1").first.wait_for()
    projector.get_by_text("2 of 3 gave it").first.wait_for()
    assert app.session.engine.state.events == poll.answer.event and app.session.presenter.selected == 1
    right = projector.locator("[data-apf=bar][data-choice='1']")
    assert "✔" in right.inner_text()
    shot(projector, "question-revealed-1024")
    within_the_caption(projector)
    pages[0].locator("p").filter(has_text="You answered robot 1: right").wait_for()
    pages[1].locator("[data-apf=mine]").filter(has_text="You answered robot 1: right").wait_for()
    shot(pages[1], "question-revealed-class-page")
    pages[2].locator("p").filter(has_text="You answered robot 0: not this time").wait_for()
    for page in (*pages, projector):
        page.close()
