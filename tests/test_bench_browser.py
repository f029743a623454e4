"""The adversary's bench and the studio in a real browser (Chromium), as their users work: branches kept
and re-entered from the History folder, and what the studio saves being what the page shows."""

from __future__ import annotations

import time
from collections.abc import Iterator

import pytest

from apf_viz.ui.app import App, demo_session, free_port
from tests.test_ui_browser import (
    _choose,
    _drag,
    blank_drawing,
    open_folder,
    open_page,
    projector_page,
    screen_of,
    shot,
    wait_for,
)

pytest.importorskip("playwright.sync_api")
pytestmark = pytest.mark.browser


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
    before = app.session.run.following_what
    page.get_by_role("combobox", name="Branches").click()
    page.get_by_role("option").filter(has_text=starts).first.click()
    page.get_by_role("button", name="Enter branch").click()
    wait_for(lambda: app.session.run.following_what not in (before, "the trace"))  # entered: a new line


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


def _text_field(page, label: str):
    """A viser text field by its label (the label's ``for`` names no input: by the row it stands in)."""
    row = page.locator(".mantine-Flex-root").filter(has=page.get_by_text(label, exact=True)).last
    return row.locator("input").first


def _undo(page) -> None:
    page.keyboard.press("Control+z")


def test_the_eraser_flood_fill_live_mirror_and_drag_painting_are_each_one_gesture_with_undo(browser, app):
    """At 1024×768: an outline filled by one click, a row erased by one drag, a cell drawn with its
    mirror image by one click, a row painted by one drag; each taken back by one Ctrl+Z."""
    s = app.session
    page, _, _ = blank_drawing(browser, app, "outline")
    page.mouse.click(*screen_of(app, page, (9, 0)))
    wait_for(lambda: s.screen.studio.anchor == (9, 0))
    page.mouse.click(*screen_of(app, page, (14, 4)))
    wait_for(lambda: len(s.editor.pattern) == 18)
    outline = set(s.editor.pattern)
    _choose(page, "Tool", "fill")
    wait_for(lambda: s.screen.studio.tool == "fill")
    page.mouse.click(*screen_of(app, page, (11, 2)))  # inside: 4 × 3 cells
    wait_for(lambda: len(s.editor.pattern) == 30)
    shot(page, "studio-filled")
    _undo(page)
    wait_for(lambda: set(s.editor.pattern) == outline)
    _choose(page, "Tool", "eraser")
    wait_for(lambda: s.screen.studio.tool == "eraser")
    time.sleep(0.5)  # the paint surface reaches the page
    _drag(page, app, (9, 0), (14, 0))  # the bottom row, by one drag
    wait_for(lambda: not outline & {(x, 0) for x in range(9, 15)} & set(s.editor.pattern))
    assert set(s.editor.pattern) == outline - {(x, 0) for x in range(9, 15)}
    _undo(page)
    wait_for(lambda: set(s.editor.pattern) == outline)  # the whole stroke, at once
    _choose(page, "Mirror", "x ↔")
    wait_for(lambda: s.screen.studio.mirror == "x ↔")  # about x = 11.5, the outline's middle
    _choose(page, "Tool", "cell")
    wait_for(lambda: s.screen.studio.tool == "cell")
    page.mouse.click(*screen_of(app, page, (9, 6)))
    wait_for(lambda: {(9, 6), (14, 6)} <= set(s.editor.pattern))
    shot(page, "studio-mirror")
    _undo(page)
    wait_for(lambda: set(s.editor.pattern) == outline)
    _choose(page, "Mirror", "off")
    wait_for(lambda: s.screen.studio.mirror == "off")
    time.sleep(0.5)
    _drag(page, app, (9, 7), (14, 7))  # painted along the drag
    wait_for(lambda: {(x, 7) for x in range(9, 15)} <= set(s.editor.pattern))
    _undo(page)
    wait_for(lambda: set(s.editor.pattern) == outline)
    page.close()


def test_save_in_edit_robots_saves_the_pattern_drawn(browser, app, tmp_path):
    from apf_viz.workbench.library import PatternLibrary

    s = app.session
    s.use_library(PatternLibrary(tmp_path / "library"))
    page, _, _ = blank_drawing(browser, app, "box")
    time.sleep(0.5)
    _drag(page, app, (9, 0), (14, 3))
    wait_for(lambda: len(s.editor.pattern) == 24)
    drawn = set(s.editor.pattern)
    _choose(page, "Mode", "Edit robots")
    wait_for(lambda: s.mode == "edit-robots")
    page.get_by_text("Robots: 10 / targets: 24").wait_for()
    field = _text_field(page, "Save as")
    field.fill("my-box")
    field.press("Enter")
    page.get_by_role("button", name="Save pattern").click()
    wait_for(lambda: "my-box" in s.saved)
    assert set(map(tuple, s.library.load("my-box"))) == drawn  # the drawing, not the run's heart
    page.close()


def test_notifications_stand_over_the_panel_never_over_the_run(browser, app):
    """The contract of ui/viser_compat.py's notification corner: a notification's box lies right of the
    canvas's run area (over the panel), whatever viser's default."""
    page, cid, screen = projector_page(browser, app)
    page.get_by_role("button", name="Frame run").click()
    from apf_viz.ui.panels.context import tell

    tell(screen.client, "Hello", "a notification")
    note = page.locator(".mantine-Notification-root").filter(has_text="a notification")
    note.wait_for()
    time.sleep(0.6)  # it slides in
    box = note.bounding_box()
    canvas = page.locator("canvas").first.bounding_box()
    panel_left = canvas["x"] + canvas["width"]
    assert box is not None and box["x"] >= panel_left - 5, (box, panel_left)
    shot(page, "notification-corner")
    note.locator(".mantine-Notification-closeButton").click()  # clicks go through it, but for its ×
    note.wait_for(state="detached")
    page.close()


def test_arrows_on_a_focused_slider_move_the_slider_only_and_f_after_a_mode_frames(browser, app):
    import numpy as np

    s = app.session
    for _ in range(30):
        s.step()
    page, _, screen = projector_page(browser, app)
    app.request_render()
    slider = page.get_by_role("slider").filter(has=page.locator("xpath=.")).nth(1)  # Speed, then Timeline
    wait_for(lambda: screen.client.camera is not None)
    time.sleep(1.0)
    before = np.array(screen.client.camera.position, dtype=float)
    slider.focus()
    page.keyboard.down("ArrowLeft")  # held: the camera turns while a key it listens to is held
    time.sleep(0.6)
    page.keyboard.up("ArrowLeft")
    wait_for(lambda: s.engine.step_index < 30)  # the timeline moved back …
    time.sleep(1.0)
    after = np.array(screen.client.camera.position, dtype=float)
    assert np.allclose(before, after, atol=1e-6), (before, after)  # … and the view did not turn
    open_folder(page, "Edit")
    _choose(page, "Mode", "Edit robots")
    wait_for(lambda: s.mode == "edit-robots")
    page.wait_for_function("document.activeElement === document.body")  # the dropdown let go
    page.keyboard.press("f")
    assert page.get_by_role("combobox", name="Mode").input_value() == "Edit robots"  # no "Edit robotsf"
    page.close()


def test_a_schedule_note_is_shown_when_its_line_is_played(browser, app):
    import json

    s = app.session
    lines = [json.dumps({"format": "apf-viz-schedule", "version": 1, "robots": s.engine.k})]
    lines.append(json.dumps({"robot": 0, "phase": "look", "note": "robot 0 looks first: watch its rays"}))
    lines.append(json.dumps({"robot": 0, "phase": "compute"}))
    s.load_schedule("noted.jsonl", ("\n".join(lines) + "\n").encode())
    page = open_page(browser, app, {"width": 1024, "height": 768})
    _click_steps(page, app, 1)
    page.get_by_text("robot 0 looks first: watch its rays").first.wait_for()
    shot(page, "schedule-note")
    _click_steps(page, app, 1)
    wait_for(lambda: s.view().note_here == "")
    page.get_by_text("robot 0 looks first: watch its rays").first.wait_for(state="hidden")
    page.close()


def test_a_refused_text_leaves_the_field_as_the_studio_holds_it(browser, app):
    s = app.session
    page, _, _ = projector_page(browser, app)
    open_folder(page, "Edit")
    _choose(page, "Mode", "Edit pattern")
    wait_for(lambda: s.mode == "edit-pattern")
    field = _text_field(page, "Text")
    field.fill("Hi! café?")
    field.press("Enter")
    page.get_by_text("no glyph").first.wait_for()  # refused, and said
    wait_for(lambda: field.input_value() == "APF")  # the field is what the next click draws
    assert s.screen.studio.text == "APF"
    page.close()


def test_j_shows_the_class_address_and_its_qr_code_on_the_projector(browser, app):
    import urllib.parse

    import segno

    page, _, _ = projector_page(browser, app)
    page.wait_for_function("document.activeElement === document.body")
    page.keyboard.press("j")
    address = page.locator("[data-apf=class-address]")
    address.wait_for()
    assert address.inner_text() == app.addresses[1]  # the class page's address, whole
    src = page.locator("[data-apf=class-qr]").get_attribute("src")
    want = segno.make(app.addresses[1], micro=False, error="m")
    assert src == want.svg_data_uri(scale=10, border=2)  # a QR code of exactly that address
    assert "this machine only" in page.locator(".mantine-Modal-body").inner_text()  # served on loopback
    assert urllib.parse.urlparse(app.addresses[1]).hostname == "127.0.0.1"
    shot(page, "join-from-the-wall")
    page.get_by_role("button", name="Close").click()
    address.wait_for(state="detached")
    page.close()


def test_a_lecture_stop_shows_the_class_address_until_the_lecture_moves_on(browser, app):
    import json

    lecture = {
        "format": "apf-viz-lecture",
        "version": 1,
        "title": "Join, then watch",
        "stops": [
            {"title": "Open your laptops", "scenario": "Heart from 10 robots", "say": "Join the class.",
             "class_address": True},
            {"title": "Ten robots", "until": {"event": 3}, "say": "Three events."},
        ],
    }  # fmt: skip
    app.session.load_lecture("join.json", json.dumps(lecture).encode())
    page = open_page(browser, app, {"width": 1024, "height": 768})
    address = page.locator("[data-apf=class-address]")
    address.wait_for()  # the first stop asks for it: shown on the presenter's page
    assert address.inner_text() == app.addresses[1]
    app.session.next_stop()
    app.request_render()
    address.wait_for(state="detached")  # the lecture moved on: closed
    page.close()


def test_j_at_a_lan_address_shows_it_on_one_line_and_escape_closes_it(browser):
    """Served to the room (--host 0.0.0.0: a LAN address, its five-digit port), J shows the address on one
    line, whole, inside its window at 1024×768; Escape closes the window (as the GUIDE says)."""
    app = App(demo_session(), host="0.0.0.0", port=free_port(), verbose=False)
    try:
        page = browser.new_page(viewport={"width": 1024, "height": 768})
        page.set_default_timeout(60_000)
        page.goto(app.addresses[0].replace("0.0.0.0", "127.0.0.1"))
        page.get_by_label("Event").wait_for()
        page.wait_for_function("document.activeElement === document.body")
        page.keyboard.press("j")
        address = page.locator("[data-apf=class-address]")
        address.wait_for()
        assert address.inner_text() == app.addresses[1] and ":" in app.addresses[1][7:]
        box = address.bounding_box()
        window = page.locator(".mantine-Modal-content").bounding_box()
        size = float(address.evaluate("e => parseFloat(getComputedStyle(e).fontSize)"))
        assert box["height"] < 1.6 * size  # one line: never broken inside the port
        assert window["x"] <= box["x"] and box["x"] + box["width"] <= window["x"] + window["width"]
        assert size >= 32  # read from the back of the room
        shot(page, "join-one-line")
        page.keyboard.press("Escape")
        address.wait_for(state="detached")
        page.keyboard.press("j")  # and it opens again
        address.wait_for()
        page.close()
    finally:
        app.stop()
