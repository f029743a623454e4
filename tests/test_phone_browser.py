"""A class page on a phone (Chromium's phone emulation: touch, a 390 × 844 screen and its landscape
844 × 390): it reaches its seat, shows the stop's question first and takes the answer by one tap on a
button, and never scrolls sideways; its caption in presentation mode is readable (16 px at least)."""

from __future__ import annotations

import json
import re
from collections.abc import Iterator

import pytest

from apf_viz.ui.app import App, demo_session, free_port
from tests.test_question_browser import LECTURE
from tests.test_ui_browser import inside_canvas, shot, wait_for

pytest.importorskip("playwright.sync_api")
pytestmark = pytest.mark.browser

PHONES = {"portrait": {"width": 390, "height": 844}, "landscape": {"width": 844, "height": 390}}
# The top of viser's bottom sheet on an upright phone: the fixed box that holds the panel's question.
SHEET_TOP_JS = (
    "() => Math.min(...[...document.querySelectorAll('*')].filter(n => getComputedStyle(n).position === "
    "'fixed' && n.innerText && n.innerText.includes('Which robot moves next?'))"
    ".map(n => n.getBoundingClientRect().top))"
)


@pytest.fixture
def app() -> Iterator[App]:
    a = App(demo_session(), port=free_port(), verbose=False)
    a.session.load_lecture("who.json", json.dumps(LECTURE).encode())
    yield a
    a.stop()


def phone_page(browser, app: App, held: str):
    """A class page on a phone held ``held`` (touch, its pixel ratio), at its seat: (its context, page)."""
    context = browser.new_context(
        viewport=PHONES[held], device_scale_factor=3, is_mobile=True, has_touch=True
    )
    page = context.new_page()
    page.set_default_timeout(60_000)
    page.goto(app.addresses[1])
    page.wait_for_url(re.compile(r"/seat/[0-9a-f]{16}-[0-9a-f]{16}$"))
    return context, page


@pytest.mark.parametrize("held", sorted(PHONES))
def test_a_class_page_on_a_phone_answers_by_one_tap_and_never_scrolls_sideways(browser, app, held):
    poll = app.session.screen.poll
    assert poll is not None
    context, page = phone_page(browser, app, held)
    try:
        question = page.get_by_text("Which robot moves next?").first
        question.wait_for()  # the page is not blank: the question, first in its panel
        wait_for(lambda: len(app.screens) == 1)
        (cid,) = app.screens
        button = page.get_by_role("button", name="robot 1", exact=True)
        button.scroll_into_view_if_needed()
        button.tap()  # one tap
        wait_for(lambda: poll.given(app.seat_of(cid)) == "1")
        page.get_by_text("Your answer: robot 1").first.wait_for()
        assert page.evaluate("document.documentElement.scrollWidth <= window.innerWidth")
        if held == "portrait":  # the run framed in the screen above the sheet, every robot whole
            cells = [r.position for r in app.session.view().robots]

            def above_the_sheet() -> bool:  # read again until it holds: the sheet opens, the camera comes
                sheet = page.evaluate(SHEET_TOP_JS)
                free = 1 - sheet / page.locator("canvas").first.bounding_box()["height"]
                return 0 < sheet < PHONES[held]["height"] and not inside_canvas(app, page, cid, cells, free)

            wait_for(above_the_sheet)
        shot(page, f"phone-{held}")
        assert poll.count == 1
    finally:
        context.close()


@pytest.mark.parametrize("held", sorted(PHONES))
def test_a_phones_caption_says_its_answer_readably(browser, app, held):
    """Presentation mode on a phone: the caption (upright, first in the bottom sheet, where viser shows
    no floating panel) at 16 px at least, with the page's own answer."""
    context, page = phone_page(browser, app, held)
    try:
        button = page.get_by_role("button", name="robot 1", exact=True)
        button.scroll_into_view_if_needed()
        button.tap()
        presentation = page.get_by_role("button", name="Presentation mode")
        presentation.scroll_into_view_if_needed()
        presentation.tap()
        words = page.locator("[data-apf=words]")
        words.wait_for()
        assert float(words.evaluate("e => parseFloat(getComputedStyle(e).fontSize)")) >= 16
        page.locator("[data-apf=mine]").filter(has_text="Your answer: robot 1").wait_for()
        assert page.evaluate("document.documentElement.scrollWidth <= window.innerWidth")
        shot(page, f"phone-{held}-caption")
    finally:
        context.close()


def test_two_phones_at_one_address_are_one_seat_and_a_made_up_seat_is_none(browser, app):
    """The server issues one seat to an address (here every page's: this machine): a second phone, with
    storage of its own, is given the same seat, and their answers are one, the last given. A page that
    opens at a seat it made up is sent to the issued one."""
    poll = app.session.screen.poll
    assert poll is not None
    first, a = phone_page(browser, app, "portrait")
    second, b = phone_page(browser, app, "portrait")
    third = browser.new_context()
    try:
        assert a.url == b.url  # the same seat, issued to the address
        for page, robot in ((a, "1"), (b, "0")):
            button = page.get_by_role("button", name=f"robot {robot}", exact=True)
            button.scroll_into_view_if_needed()
            button.tap()
        wait_for(lambda: poll.given(app.seat_of(max(app.screens))) == "0")
        assert poll.count == 1
        made_up = third.new_page()
        made_up.goto(a.url.split("?")[0] + "?websocket=" + a.url.split("websocket=")[1][:-33] + "0" * 16
                     + "-" + "0" * 16)  # fmt: skip
        made_up.wait_for_url(a.url)  # sent to the seat the server issued
        assert poll.count == 1
    finally:
        for context in (first, second, third):
            context.close()
