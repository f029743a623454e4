"""The visualiser in a real headless Chromium (Debian's /usr/bin/chromium, driven by Playwright).

Screenshots go to test-output/; look at them. The server runs in-process on a free port, so tests can
also read the shared Session to check that a click reached the engine.
"""

from __future__ import annotations

import html
import json
import random
import time
from collections.abc import Iterator
from io import BytesIO
from pathlib import Path

import imageio.v3 as iio
import numpy as np
import pytest
from PIL import Image, ImageSequence

from apf_viz.algorithms.apf_opaque_grid.audit import random_pattern, random_solvable_start
from apf_viz.core import shapes
from apf_viz.core.formats import load_trace
from apf_viz.ui.app import App, demo_session, free_port
from apf_viz.ui.browser_screen import inside as _inside
from apf_viz.workbench.session import Session

playwright = pytest.importorskip("playwright.sync_api")
CHROMIUM = "/usr/bin/chromium"
OUT = Path(__file__).resolve().parent.parent / "test-output"
ARGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]
VIEWPORT = {"width": 1400, "height": 900}
pytestmark = pytest.mark.browser  # bash scripts/test.sh -m "not browser": the quick subset

if not Path(CHROMIUM).exists():  # the README's test command installs it; say so instead of skipping quietly
    pytest.fail(
        f"{CHROMIUM} is missing: run bash scripts/test.sh, which installs Debian's chromium", pytrace=False
    )


@pytest.fixture
def app() -> Iterator[App]:
    # Several class pages from this one machine, each a laptop of its own (a hall behind one router).
    a = App(demo_session(), port=free_port(), verbose=False, seats_per_address=8)
    yield a
    a.stop()


def open_page(browser, app: App, viewport: dict | None = None):
    before = set(app.screens)
    page = browser.new_page(viewport=viewport or VIEWPORT)
    page.set_default_timeout(60_000)  # waits for behaviour; a loaded machine is only slower
    page.goto(app.addresses[0])  # the presenter address
    page.get_by_label("Event").wait_for()
    wait_for(lambda: set(app.screens) - before)
    drawn_there(app, page)
    return page


def drawn_there(app: App, page) -> None:
    """Two frames drawn from now (the first may have begun before), then two of the browser's own: what
    the server sent the page is drawn there (instead of a fixed wait for "the first frames")."""
    for _ in range(2):
        frames = app.frames
        app.request_render()
        wait_for(lambda frames=frames: app.frames > frames)
    page.evaluate("() => new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))")


def settled(app: App, screen) -> None:
    """A frame drawn for the run as it is, and the browser's camera at the last pose sent to it (a
    framed camera follows the run: its pose is the projection the checks use)."""
    frames = app.frames
    app.request_render()
    wait_for(lambda: app.frames > frames)
    try:
        wait_for(lambda: screen._acknowledged or screen.state.camera == "moved")
    except AssertionError:
        raise AssertionError(
            f"the page's camera never reported the pose sent: sent {screen._sent}, "
            f"reported {screen._reported}, camera {screen.state.camera}"
        ) from None


def projector_page(browser, app: App):
    """A 1024×768 page, the only browser: (the page, its client id, its screen)."""
    page = open_page(browser, app, {"width": 1024, "height": 768})
    wait_for(lambda: len(app.screens) == 1)
    (cid,) = app.screens
    return page, cid, app.screens[cid]


def open_folder(page, title: str) -> None:
    """Expand one of the folders that start collapsed (Algorithm, Edit, Files, Moves over events)."""
    page.get_by_text(title, exact=True).first.click()
    time.sleep(0.3)


def event_value(page) -> int:
    return int(page.get_by_label("Event").input_value())


def wait_for(predicate, timeout: float = 60.0) -> None:
    """Wait for behaviour, however loaded the machine (a timeout is a deadlock guard, not a speed test)."""
    end = time.time() + timeout
    while time.time() < end:
        if predicate():
            return
        time.sleep(0.1)
    raise AssertionError("condition not met in time")


def downloaded(page, button) -> tuple[str, bytes]:
    """Click a button that downloads a file; its name and bytes (saved at once: no link is left)."""
    with page.expect_download(timeout=60_000) as download:
        button.click()
    return download.value.suggested_filename, Path(download.value.path()).read_bytes()


def shot(page, name: str) -> Path:
    OUT.mkdir(exist_ok=True)
    path = OUT / f"{name}.png"
    page.screenshot(path=str(path))
    return path


def screen_of(app: App, page, cell: tuple[int, int]) -> tuple[float, float]:
    """Project a grid point onto the page through the camera of the presenter's browser (the first to
    connect) as it is now (it follows the run), or the initial camera before any browser reports one."""
    wait_for(lambda: bool(app.screens))
    presenter = next((x for x in app.screens.values() if x.state is app.session.presenter), None)
    if presenter is not None:  # a run stepped without a frame: let its camera follow it first
        app.request_render()
        box = presenter.state
        wait_for(lambda: box.camera == "moved" or _inside(app.renderer.bounds, box.framed_bounds))
        time.sleep(0.5)  # the pose reaches the browser (it may report none: a pose it already has)
    try:
        camera = presenter.client.camera
        position, look_at, fov = camera.position, camera.look_at, float(camera.fov)
    except (AttributeError, AssertionError):
        position, look_at, fov = app.renderer.framed_pose
    p, target = np.array(position, dtype=float), np.array(look_at, dtype=float)
    f = (target - p) / np.linalg.norm(target - p)
    r = np.cross(f, [0.0, 0.0, 1.0])
    r /= np.linalg.norm(r)
    u = np.cross(r, f)
    d = np.array([*app.renderer.to_scene(cell), 0.0]) - p
    box = page.locator("canvas").first.bounding_box()
    w, h = box["width"], box["height"]
    t = np.tan(fov / 2)
    ndc_x = (d @ r) / ((d @ f) * t * (w / h))
    ndc_y = (d @ u) / ((d @ f) * t)
    return box["x"] + (1 + ndc_x) * w / 2, box["y"] + (1 - ndc_y) * h / 2


def test_page_connects_and_the_canvas_is_not_blank(browser, app):
    page = open_page(browser, app)
    path = shot(page, "connected")
    canvas = page.locator("canvas").first.screenshot()
    pixels = np.asarray(Image.open(BytesIO(canvas)).convert("RGB"), dtype=np.int32)
    assert pixels.std() > 5, "the canvas is blank"
    colours = {tuple(c) for c in pixels.reshape(-1, 3)[::97]}
    assert len(colours) > 20
    assert path.exists()
    page.close()


def test_step_advances_event_and_back_restores_it(browser, app):
    page = open_page(browser, app)
    assert event_value(page) == 0
    page.get_by_role("button", name="Step").click()
    wait_for(lambda: event_value(page) == 1)
    for _ in range(4):
        page.get_by_role("button", name="Step").click()
    wait_for(lambda: event_value(page) == 5)
    page.get_by_role("button", name="Back").click()
    wait_for(lambda: event_value(page) == 4)
    assert app.session.view().steps == 4
    shot(page, "after-step-back")
    page.close()


def test_play_turns_into_pause_and_runs(browser, app):
    page = open_page(browser, app)
    page.get_by_role("button", name="Play").click()
    page.get_by_role("button", name="Pause").wait_for()
    wait_for(lambda: event_value(page) > 5)
    page.get_by_role("button", name="Pause").click()
    page.get_by_role("button", name="Play").wait_for()
    wait_for(lambda: not app.session.playing)
    frozen = app.session.view().event
    wait_for(lambda: event_value(page) == frozen)  # the page catches up, however loaded the machine
    for _ in range(3):  # and nothing moves on while paused
        app.request_render()
        time.sleep(0.3)
        assert app.session.view().event == frozen and event_value(page) == frozen
    page.close()


def test_manual_mode_a_click_on_a_robot_runs_its_next_phase(browser, app):
    page = open_page(browser, app)
    page.get_by_label("Scheduler").click()
    page.get_by_role("option", name="Manual").click()
    wait_for(lambda: app.session.scheduler_name == "manual")
    robot = 4
    cell = app.session.engine.current_points()[robot]
    x, y = screen_of(app, page, cell)
    page.mouse.click(x, y)
    wait_for(lambda: app.session.engine.next_event(robot) == "compute")
    page.mouse.click(x, y)
    wait_for(lambda: app.session.engine.next_event(robot) == "move")
    wait_for(lambda: event_value(page) == 2)
    assert all(app.session.engine.next_event(r) == "look" for r in range(10) if r != robot)
    page.get_by_text("Manual — click a robot").wait_for()
    shot(page, "manual-click")
    page.close()


def test_edit_pattern_clicks_change_the_target_count(browser, app):
    page = open_page(browser, app)
    open_folder(page, "Edit")
    chosen(page, "Mode", "Edit pattern", lambda: app.session.mode == "edit-pattern")
    page.get_by_role("button", name="Clear pattern").click()
    page.get_by_text("Targets: 0 / robots: 10").wait_for()
    for cell in [(1, 1), (2, 1), (3, 1)]:
        x, y = screen_of(app, page, cell)
        page.mouse.click(x, y)
        time.sleep(0.2)
    page.get_by_text("Targets: 3 / robots: 10").wait_for()
    assert sorted(app.session.editor.pattern) == [(1, 1), (2, 1), (3, 1)]
    shot(page, "edit-pattern")
    # Back to Run with 3 targets for 10 robots: refused, the drawing is kept.
    page.get_by_role("combobox", name="Mode").click()
    page.get_by_role("option", name="Run").click()
    page.get_by_text("the pattern has 3 points but there are 10 robots").wait_for()
    assert app.session.mode == "edit-pattern" and len(app.session.editor.pattern) == 3
    page.close()


def test_a_malformed_upload_shows_a_notification_and_keeps_the_run(browser, app, tmp_path):
    page = open_page(browser, app)
    page.get_by_role("button", name="Step").click()
    wait_for(lambda: event_value(page) == 1)
    bad = tmp_path / "broken.json"
    bad.write_text('{"points": [[0, 0], [0, 0]]}')
    with page.expect_file_chooser() as chooser:
        open_folder(page, "Files")
        page.get_by_role("button", name="Upload pattern").click()
    chooser.value.set_files(str(bad))
    page.get_by_text("duplicate pattern point at (0, 0)").wait_for()
    shot(page, "bad-upload")
    assert event_value(page) == 1 and app.session.view().steps == 1
    lecture = tmp_path / "lecture.json"  # a lecture whose second stop runs to two things at once
    first = {"title": "a", "say": "b", "scenario": "Heart from 10 robots"}
    second = {"title": "c", "say": "d", "until": {"event": 3, "rule": "A1.off.terminal"}}
    lecture.write_text(
        json.dumps({"format": "apf-viz-lecture", "version": 1, "title": "t", "stops": [first, second]})
    )
    with page.expect_file_chooser() as chooser:
        page.get_by_role("button", name="Upload lecture").click()
    chooser.value.set_files(str(lecture))
    page.get_by_text("lecture.json: stops[1].until: give exactly one of").wait_for()
    assert app.session.view().steps == 1 and app.session.lecturer is None  # the run and no lecture kept
    page.close()


def test_a_second_page_sees_the_first_pages_steps(browser, app):
    first = open_page(browser, app)
    second = open_page(browser, app)
    for _ in range(3):
        first.get_by_role("button", name="Step").click()
    wait_for(lambda: event_value(second) == 3)
    shot(second, "second-page")
    first.close()
    second.close()


def test_save_screenshot_downloads_the_view_as_a_png(browser, app):
    page = open_page(browser, app)
    for _ in range(3):
        page.get_by_role("button", name="Step").click()
    wait_for(lambda: event_value(page) == app.session.view().event > 0)
    open_folder(page, "Files")
    name, data = downloaded(page, page.get_by_role("button", name="Save screenshot"))
    assert name == f"apf-viz-event-{event_value(page)}.png"
    image = iio.imread(bytes(data), extension=".png")
    OUT.mkdir(exist_ok=True)
    (OUT / "saved-screenshot.png").write_bytes(bytes(data))
    box = page.locator("canvas").first.bounding_box()
    assert image.ndim == 3 and image.shape[2] == 3  # the transparent canvas flattened onto white
    # For a slide: the canvas at its own resolution, the legend beside it, the caption under it.
    w, h = round(box["width"]), round(box["height"])
    assert image.shape[1] > w + 200 and image.shape[0] > h
    canvas, column = image[:h, :w].astype(np.int32), image[:, w + 1 :].astype(np.int32)
    assert np.median(canvas) > 230  # the page's white background, not black
    green = (canvas[:, :, 1] > canvas[:, :, 0] + 50) & (canvas[:, :, 1] > canvas[:, :, 2] + 50)
    assert green.sum() > 200, "the pattern's target cells are not in the saved image"
    for light in app.session.view().lights_in_use:  # each light in use has its swatch in the legend
        color = np.array(app.session.view().legend[light].color)
        assert (np.abs(column - color).max(axis=2) <= 2).sum() > 20, light
    dark_text = (image[h:].astype(np.int32).max(axis=2) < 80).sum()
    assert dark_text > 300  # the caption's words under the picture
    page.get_by_label("With legend, caption").uncheck()
    name, data = downloaded(page, page.get_by_role("button", name="Save screenshot"))
    plain = iio.imread(bytes(data), extension=".png")
    assert abs(plain.shape[1] / plain.shape[0] - box["width"] / box["height"]) < 0.05  # the view alone
    page.close()


def test_save_figure_downloads_what_the_page_shows_as_svg_and_tikz(browser, app):
    """Save figure (Files): the page's view, its selected robot's rays included, as SVG and TikZ in a zip
    named after the event shown; the presenter's selection is not changed by it."""
    import io
    import xml.etree.ElementTree as ET
    import zipfile

    page = open_page(browser, app)
    for _ in range(40):
        page.keyboard.press("Enter")
    wait_for(lambda: event_value(page) == app.session.view().event >= 40)
    app.session.selected = 1
    app.request_render()
    open_folder(page, "Files")
    name, data = downloaded(page, page.get_by_role("button", name="Save figure"))
    event = app.session.view().event
    assert name == f"apf-viz-event-{event}.zip" and app.session.selected == 1
    with zipfile.ZipFile(io.BytesIO(data)) as z:
        assert sorted(z.namelist()) == [f"apf-viz-event-{event}.svg", f"apf-viz-event-{event}.tex"]
        svg = ET.fromstring(z.read(f"apf-viz-event-{event}.svg"))
        tikz = z.read(f"apf-viz-event-{event}.tex").decode()
    view = app.session.view()
    lines = [e for e in svg.iter("{http://www.w3.org/2000/svg}line") if e.get("stroke") == "rgb(250,200,0)"]
    assert len(lines) == len(view.rays) > 0  # the selected robot's rays
    assert tikz.startswith(r"\begin{tikzpicture}") and f"event {event}" in tikz
    page.close()


def test_export_page_downloads_the_run_so_far_without_moving_it(browser, app):
    page = open_page(browser, app)
    for _ in range(12):
        page.keyboard.press("Enter")
    wait_for(lambda: event_value(page) == app.session.view().event >= 12)
    steps = app.session.engine.step_index
    open_folder(page, "Files")
    name, data = downloaded(page, page.get_by_role("button", name="Export page"))
    assert name == f"apf-viz-run-event-{app.session.view().event}.html"
    assert b"window.__VISER_EMBED_DATA__" in data and len(data) < 15_000_000
    assert app.session.engine.step_index == steps  # recorded on a copy: the run did not move
    page.close()


def test_record_gif_records_the_steps_taken_meanwhile(browser, app):
    page = open_page(browser, app)
    started = time.perf_counter()
    open_folder(page, "Files")
    page.get_by_role("button", name="Record GIF").click()
    page.get_by_role("button", name="Stop recording").wait_for()
    wait_for(lambda: app.panels._recorder is not None)
    recording = app.panels._recorder

    def a_new_frame() -> None:  # paced by the recorder, not by the clock: a loaded machine is slower
        n = len(recording.frames)
        wait_for(lambda: len(recording.frames) > n, timeout=60)

    for step in range(1, 4):
        a_new_frame()
        page.get_by_role("button", name="Step").click()
        wait_for(lambda step=step: app.session.view().event == step)
    a_new_frame()
    a_new_frame()  # one asked for after the last step's frame was drawn
    name, data = downloaded(page, page.get_by_role("button", name="Stop recording"))
    ended = time.perf_counter() - started
    assert name == f"apf-viz-events-0-{event_value(page)}.gif"
    OUT.mkdir(exist_ok=True)
    (OUT / "recorded.gif").write_bytes(bytes(data))
    frames = iio.imread(bytes(data), extension=".gif", index=None)
    assert frames.ndim == 4 and len(frames) >= 3  # at least the frames waited for (repeats merge)
    assert not all(np.array_equal(frames[0], f) for f in frames[1:]), "every frame is the same"
    with Image.open(BytesIO(bytes(data))) as gif:  # frame by frame: the encoder merges repeated frames
        durations = [frame.info["duration"] / 1000 for frame in ImageSequence.Iterator(gif)]
    assert min(durations) >= 0.25  # never faster than 4 frames a second (by construction)
    # The recording lies within the clicks that started and stopped it, so it cannot play longer than
    # that, however loaded the machine; that it plays in real time on the recorder's own clock is
    # tests/test_recorder.py's job (a bound on wall time from below is a bound on the machine's load).
    assert sum(durations) <= ended + 0.01 * len(durations)  # GIF keeps hundredths of a second
    page.get_by_role("button", name="Record GIF").wait_for()  # ready for the next one
    page.close()


def test_the_moves_plot_reads_events_on_its_x_axis_not_dates(browser, app):
    for _ in range(120):
        app.session.step()
    app.request_render()
    page = open_page(browser, app)
    from playwright.sync_api import Error as PlaywrightError

    open_folder(page, "Moves over events")
    seen: list[str] = []

    def legend_under_the_cursor() -> bool:
        """Hover the plot (its legend shows the values under the cursor) and read the legend. The plot
        may be mounted again while its data arrives, detaching the one found: then hover the new one."""
        try:
            page.locator(".uplot .u-over").first.hover(timeout=10_000)
            seen.append(" ".join(page.locator(".uplot .u-legend").first.inner_text(timeout=10_000).split()))
        except PlaywrightError:
            return False
        return "moves" in seen[-1] and any(c.isdigit() for c in seen[-1])

    wait_for(legend_under_the_cursor)
    text = seen[-1]
    event = text.split("event")[1].split("moves")[0].strip(" :")
    assert event.isdigit() and int(event) <= app.session.view().event, text
    page.close()


def test_why_panel_lists_the_predicates_and_the_canvas_shades_the_regions(browser, app):
    for _ in range(25):
        app.session.step()
    decided = [r for r in range(10) if app.session.engine.state.decided[r] is not None]
    assert decided
    page = open_page(browser, app)
    r = decided[0]
    x, y = screen_of(app, page, app.session.engine.current_points()[r])
    page.mouse.click(x, y)
    wait_for(lambda: app.session.selected == r)
    why = app.session.view().why
    assert why is not None and why.explanation is not None
    page.get_by_text(f"Robot {r} · rule").wait_for()
    page.get_by_text(why.explanation.decision.rule_id, exact=True).first.wait_for()
    table = page.locator("table").filter(has_text="what it found").first
    table.wait_for()
    text = table.inner_text()
    assert "✔" in text and "✘" not in text  # every test read as a statement that holds
    assert any(n.startswith("/why/") for n in app.drawn())
    if why.regions:  # numbered in the panel as on the canvas, each in its own colour
        page.get_by_text("Regions it tested").wait_for()
        tags = [h.text for n, h in app.drawn().items() if n.startswith("/why/labels/") and h.visible]
        assert sorted(t.split(" · ")[0] for t in tags) == [str(i + 1) for i in range(len(tags))]
    shot(page, "why-panel")
    page.set_viewport_size({"width": 1024, "height": 768})
    drawn_there(app, page)
    shot(page, "why-panel-1024")
    page.close()


def test_switching_the_algorithm_to_the_literal_paper_and_back(browser, app):
    page = open_page(browser, app)
    for _ in range(5):
        page.get_by_role("button", name="Step").click()
    wait_for(lambda: app.session.engine.step_index >= 5)
    open_folder(page, "Algorithm")
    page.get_by_role("combobox", name="Algorithm").click()
    page.get_by_role("option", name="apf-opaque-grid-literal").click()
    wait_for(lambda: app.session.engine.algorithm.name == "apf-opaque-grid-literal")
    assert app.session.engine.step_index == 0  # the run restarted on the same start and pattern
    page.get_by_role("combobox", name="Algorithm").click()
    page.get_by_role("option", name="apf-opaque-grid", exact=True).click()
    wait_for(lambda: app.session.engine.algorithm.name == "apf-opaque-grid")
    variant = page.locator("xpath=//*[text()='Variant']/following::input[1]")
    wait_for(lambda: variant.input_value() == "apf-opaque-grid")  # the field follows the algorithm
    variant.fill("apf-opaque-grid@G1,LA")
    page.get_by_role("button", name="Use variant").click()
    wait_for(lambda: app.session.engine.algorithm.name == "apf-opaque-grid@G1,LA")
    page.close()


def test_a_merged_light_variant_runs_beside_the_algorithm_and_a_bad_merge_is_one_line(browser, app):
    page = open_page(browser, app)
    open_folder(page, "Algorithm")
    variant = page.locator("xpath=//*[text()='Variant']/following::input[1]")
    variant.fill("apf-opaque-grid+merge(leader1=leader1)")
    page.get_by_role("button", name="Use variant").click()
    page.get_by_text("a light is one colour already").first.wait_for()
    assert app.session.engine.algorithm.name == "apf-opaque-grid"  # the run is kept
    assert variant.input_value() == "apf-opaque-grid+merge(leader1=leader1)"  # and so is what was typed
    variant.fill("apf-opaque-grid+merge(leader1=decider)")
    page.get_by_role("button", name="Use variant").click()
    wait_for(lambda: app.session.engine.algorithm.name == "apf-opaque-grid+merge(leader1=decider)")
    page.get_by_text("leader1 = decider (merged)").first.wait_for()  # the legend names both lights
    open_folder(page, "Compare")
    page.locator("xpath=//*[text()='Compare with']/following::input[1]").fill("apf-opaque-grid")
    page.get_by_role("button", name="Compare", exact=True).click()
    page.get_by_text("B apf-opaque-grid").first.wait_for()
    engine = app.session.engine
    for n in range(1, 31):  # (on this start the merge gets stuck at step 28: the deciders are lost)
        page.get_by_role("button", name="Step").click()
        wait_for(lambda n=n: engine.step_index == n or engine.finished)
        if engine.finished:
            break
    assert engine.step_index > 10 and "decider" not in engine.state.lights_used
    page.get_by_role("button", name="Frame run").click()
    shot(page, "merged-variant-compared")
    page.close()


def test_verify_breaks_a_merged_variant_and_the_labs_counterexample_plays_as_a_demo(browser, app):
    """The light-budget lab in a lecture (docs/LIGHTS.md): merge two lights, Verify finds the schedule
    that breaks it on the current start; the lab's kept counterexample is a Demo that plays to the end."""
    page = open_page(browser, app, {"width": 1024, "height": 768})
    page.get_by_role("combobox", name="Demo").click()
    page.get_by_role("option", name="One robot on L1").click()
    wait_for(lambda: app.session.engine.k == 3)
    open_folder(page, "Algorithm")
    page.get_by_role("combobox", name="Two lights as one").click()  # picked, not typed
    page.get_by_role("option", name="leader1 shown as decider").click()
    wait_for(lambda: app.session.engine.algorithm.name == "apf-opaque-grid+merge(decider=leader1)")
    page.get_by_role("button", name="Verify").click()
    page.get_by_text("Verify: deadlock").wait_for(timeout=120_000)
    wait_for(lambda: app.session.view().trace_position is not None)
    while app.session.step():
        pass
    app.request_render()
    page.get_by_role("heading", name="⊘ STUCK").wait_for()
    assert app.session.engine.history.events()[-1].rule.endswith("(leader1 is shown as decider: merged)")
    shot(page, "merged-variant-verify")
    page.get_by_role("combobox", name="Demo").click()
    page.get_by_role("option", name="Two lights as one: decider shown as leader1").click()
    page.get_by_text("apf-viz lights found it").first.wait_for()
    wait_for(lambda: app.session.engine.algorithm.name == "apf-opaque-grid+merge(leader1=decider)")
    merge = page.get_by_role("combobox", name="Two lights as one")
    wait_for(lambda: merge.input_value() == "decider shown as leader1")  # the folder follows the run
    while app.session.step():
        pass
    app.request_render()
    page.get_by_role("heading", name="⊘ STUCK").wait_for()
    assert app.session.engine.step_index == 10
    shot(page, "merged-variant-demo")
    page.close()


def test_the_example_algorithms_legend_shows_its_lights(browser):
    from apf_viz.workbench.session import Session

    session = Session(
        [(0, 0), (3, 0), (5, 1), (2, 2), (6, 3)], [(x, 0) for x in range(5)], algorithm="compact-left"
    )
    other = App(session, port=free_port(), verbose=False)
    try:
        page = open_page(browser, other)
        page.get_by_text("still sliding left").wait_for()
        page.get_by_text("the wall: the leftmost column").first.wait_for()
        assert page.get_by_text("terminal1", exact=True).count() == 0  # not the paper's legend
        shot(page, "example-algorithm")
        page.close()
    finally:
        other.stop()


def test_last_event_next_move_and_frame_run(browser, app):
    page = open_page(browser, app)
    other = open_page(browser, app)  # a second browser on the same run (a projector, say)
    page.get_by_role("button", name="Step").click()
    wait_for(lambda: app.session.engine.step_index == 1)
    last = page.locator("p", has_text="Last event:").first
    wait_for(lambda: "· Look: sees" in last.inner_text())
    page.get_by_role("button", name="Next move").click()
    page.get_by_text("a robot moved after").wait_for()
    wait_for(lambda: app.session.engine.state.moves == 1)
    wait_for(lambda: "· Move → (" in last.inner_text())
    time.sleep(1.0)
    assert other.get_by_text("a robot moved after").count() == 0  # told only the browser that asked
    page.get_by_role("button", name="Frame run").click()
    shot(page, "last-event")
    page.close()
    other.close()


def test_a_collision_is_shown_with_the_robots_and_the_cell(browser, app):
    trace = Path(__file__).parent / "literal_traces" / "collision.jsonl"
    app.session.load_trace(trace.name, trace.read_bytes())
    while app.session.engine.redo() is not None:
        pass
    app.request_render()
    page = open_page(browser, app)
    page.get_by_role("heading", name="✖ COLLISION").wait_for()
    page.get_by_text("on a snapshot taken at step").wait_for()
    shot(page, "collision")
    page.close()


def test_step_follows_a_loaded_trace_and_branch_here_leaves_it(browser, app):
    trace = Path(__file__).parent / "literal_traces" / "collision.jsonl"
    app.session.load_trace(trace.name, trace.read_bytes())
    recorded = app.session.engine.history.events()
    app.request_render()
    page = open_page(browser, app)
    for _ in range(3):
        page.get_by_role("button", name="Step").click()
    wait_for(lambda: app.session.engine.step_index == 3)
    assert app.session.engine.history.events(3) == recorded[: len(app.session.engine.history.events(3))]
    page.get_by_text("Following the trace: event").wait_for()
    page.get_by_role("button", name="Branch here").click()
    wait_for(lambda: app.session.view().trace_position is None)
    page.get_by_role("button", name="Branch here").wait_for(state="hidden")
    page.close()


def _serve_args(*argv: str):
    from apf_viz.cli import build_parser

    return build_parser().parse_args(["serve", *argv])


def test_serve_trace_of_a_check_counterexample_steps_41_times_to_a_located_collision(browser, tmp_path):
    """The issue's recipe: `apf-viz check … --counterexample cex.jsonl`, then `apf-viz serve --trace`."""
    from apf_viz.cli import main
    from apf_viz.cli.serve import session_config
    from apf_viz.demos import demo_dir
    from apf_viz.workbench.config import session_from_config

    cex = tmp_path / "cex.jsonl"
    demos = demo_dir()
    code = main(
        [
            "check",
            "--robots",
            str(demos / "starts" / "vertical-line-4.json"),
            "--pattern",
            str(demos / "tee-4.json"),
            "--algorithm",
            "apf-opaque-grid-literal",
            "--counterexample",
            str(cex),
        ]
    )
    assert code == 1 and cex.is_file()
    served = App(
        session_from_config(session_config(_serve_args("--trace", str(cex)))), port=free_port(), verbose=False
    )
    try:
        page = open_page(browser, served)
        page.get_by_text("Following the trace: event").wait_for()
        step = page.get_by_role("button", name="Step")
        for n in range(1, 42):
            step.click()
            wait_for(lambda n=n: served.session.engine.step_index == n)  # one event per click
        page.get_by_role("heading", name="✖ COLLISION").wait_for()
        last = page.locator("p", has_text="Last event:").first
        wait_for(lambda: last.inner_text().endswith("robot 3 · Move → (0, 1) on the grid: COLLISION"))
        page.get_by_text("robot 3 moved onto robot 1 at (0, 1)").first.wait_for()
        page.get_by_text("event 41 of 41 — its end").wait_for()
        shot(page, "cex-collision")
        for _ in range(11):
            page.get_by_role("button", name="Back").click()
        wait_for(lambda: served.session.engine.step_index == 30)
        page.get_by_role("button", name="Branch here").click()
        wait_for(lambda: served.session.view().trace_position is None)
        step.click()  # now the ASYNC scheduler chooses
        wait_for(lambda: served.session.engine.step_index == 31)
        assert served.session.view().trace_position is None
        page.close()
    finally:
        served.stop()


def test_the_demo_played_to_formed_keeps_the_robots_on_the_target_cells(browser, app):
    page = open_page(browser, app)
    speed = page.locator("xpath=//*[text()='Speed']/following::input[2]")
    speed.fill("5000")
    speed.press("Enter")
    wait_for(lambda: app.session.speed == 5000)
    page.get_by_role("button", name="Play").click()
    page.get_by_role("heading", name="✔ FORMED").wait_for(timeout=300_000)
    v = app.session.view()
    assert v.outcome == "formed"
    assert {r.position for r in v.robots} == set(v.targets)  # the targets stayed where the pattern formed
    drawn = np.asarray(app.renderer.nodes()["/targets"].points)[:, :2]
    assert {app.renderer.to_scene(p) for p in v.targets} == {tuple(map(float, p)) for p in drawn}
    shot(page, "formed")
    page.close()


def test_frame_run_after_reset_points_the_camera_at_the_run(browser, app):
    page = open_page(browser, app)
    client = next(iter(app.server.get_clients().values()))
    framed = np.array(app.renderer.framed_pose[0])
    box = page.locator("canvas").first.bounding_box()
    page.mouse.move(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)  # clear of notifications
    for _ in range(8):
        page.mouse.wheel(0, 400)  # zoom far out
        time.sleep(0.1)
    wait_for(lambda: np.linalg.norm(np.array(client.camera.position) - framed) > 1.0)
    page.get_by_role("button", name="Reset").click()
    page.get_by_role("button", name="Frame run").click()
    fitted = np.array(app.renderer.camera_pose(client.camera.aspect)[0])  # fitted to this canvas
    wait_for(lambda: np.linalg.norm(np.array(client.camera.position) - fitted) < 0.05)
    x0, y0, x1, y1 = app.renderer.bounds
    assert abs(fitted[0] - (x0 + x1) / 2) < 1e-6  # centred on the run
    page.close()


def test_a_crowd_framed_whole_hides_the_y_axis_diamonds_and_zooming_in_brings_them_back(browser):
    rng = random.Random(3)
    crowd = App(Session(random_solvable_start(1000, rng), random_pattern(1000, rng)), port=free_port())
    try:
        page = open_page(browser, crowd)
        noses = lambda: crowd.renderer.nodes()["/robots/y_axes"]  # noqa: E731
        wait_for(lambda: noses().visible is False)  # framed whole: a diamond would be a pixel
        box = page.locator("canvas").first.bounding_box()
        page.mouse.move(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
        for _ in range(12):
            page.mouse.wheel(0, -400)  # zoom far in
            time.sleep(0.1)
        wait_for(lambda: noses().visible and len(noses().points) == 1000)
        for _ in range(12):
            page.mouse.wheel(0, 400)
            time.sleep(0.1)
        wait_for(lambda: noses().visible is False)
        page.close()
    finally:
        crowd.stop()


def test_a_hint_goes_only_to_the_page_that_caused_it(browser, app):
    app.session.set_scheduler("Manual")
    app.request_render()
    page = open_page(browser, app)
    projector = open_page(browser, app)
    page.get_by_role("button", name="Step").click()  # Manual, nothing selected: a hint for this page
    page.get_by_text("Manual: click a robot to run its next phase").wait_for()
    time.sleep(1.0)
    assert projector.get_by_text("Manual: click a robot to run its next phase").count() == 0
    page.close()
    projector.close()


def test_click_select_shows_a_snapshot_without_advancing_in_manual(browser, app):
    app.session.set_scheduler("Manual")
    app.request_render()
    page = open_page(browser, app)
    r = 2
    at = app.session.engine.current_points()[r]
    page.mouse.click(*screen_of(app, page, at))
    wait_for(lambda: app.session.engine.step_index == 1)  # advance (the default): robot 2 looks
    page.get_by_role("combobox", name="Click").click()
    page.get_by_role("option", name="select").click()
    wait_for(lambda: not app.session.click_advances)
    page.get_by_text("Manual, Click: select").wait_for()
    other = app.session.engine.current_points()[5]
    page.mouse.click(*screen_of(app, page, other))
    wait_for(lambda: app.session.selected == 5)
    assert app.session.engine.step_index == 1  # selected, not advanced
    page.get_by_text("Idle: rays show the").wait_for()
    page.close()


def test_the_demo_dropdown_loads_a_scenario_and_says_what_it_shows(browser, app):
    page = open_page(browser, app)
    page.get_by_role("combobox", name="Demo").click()
    page.get_by_role("option", name="The literal paper collides").click()
    page.get_by_text("Following the trace: event").wait_for()
    page.get_by_text("Step follows the 41 events to the collision").wait_for()
    wait_for(lambda: app.session.run.trace_events == 41)
    page.get_by_role("combobox", name="Demo").click()
    page.get_by_role("option", name="Unsolvable box").click()
    wait_for(lambda: app.session.mode == "edit-robots")
    wait_for(lambda: page.get_by_text("Following the trace").count() == 0)  # nothing of the last run left
    page.get_by_text("cannot be solved").first.wait_for()
    shot(page, "demo-unsolvable")
    page.close()


def test_a_livelocks_loop_is_marked_on_the_timeline(browser, app, tmp_path):
    import json

    source = (Path(__file__).parent / "literal_traces" / "collision.jsonl").read_text().splitlines()
    header = json.loads(source[0])
    header["options"] = {"verdict": "livelock", "loop_starts_at_step": 20}  # as check writes one
    trace = tmp_path / "loop.jsonl"
    trace.write_text("\n".join([json.dumps(header), *source[1:]]) + "\n")
    app.session.load_trace(trace.name, trace.read_bytes())
    app.request_render()
    page = open_page(browser, app)
    page.get_by_text("loop starts").wait_for()
    page.get_by_text("loop repeats").wait_for()
    page.get_by_text("verdict: livelock").wait_for()
    page.close()


def test_download_schedule_after_manual_clicks_then_upload_schedule_on_a_reset_run_replays_them(
    browser, app, tmp_path
):
    app.session.set_scheduler("Manual")
    app.request_render()
    page = open_page(browser, app)
    at = app.session.engine.current_points()[2]
    for n in range(1, 4):  # robot 2: Look, Compute, Move
        page.mouse.click(*screen_of(app, page, at))
        wait_for(lambda n=n: app.session.engine.step_index == n)
    clicked = app.session.engine.history.events()
    open_folder(page, "Files")
    name, data = downloaded(page, page.get_by_role("button", name="Download schedule"))
    assert name == "schedule.jsonl"
    text = data.decode()
    assert [json.loads(line) for line in text.splitlines()[1:]] == [
        {"robot": 2, "phase": p} for p in ("look", "compute", "move")
    ]
    saved = tmp_path / "schedule.jsonl"
    saved.write_text(text)
    page.get_by_role("button", name="Reset").click()
    wait_for(lambda: app.session.engine.step_index == 0)
    with page.expect_file_chooser() as chooser:
        page.get_by_role("button", name="Upload schedule").click()
    chooser.value.set_files(str(saved))
    page.get_by_text("Following the schedule schedule.jsonl: event").wait_for()
    for n in range(1, 4):
        page.get_by_role("button", name="Step").click()
        wait_for(lambda n=n: app.session.engine.step_index == n)
    assert app.session.engine.history.events() == clicked
    page.close()


def verify_demo(page, app: App, name: str, k: int) -> None:
    """Choose a Demo scenario of k robots and press Verify."""
    page.get_by_role("combobox", name="Demo").click()
    page.get_by_role("option", name=name).click()
    wait_for(lambda: app.session.engine.k == k)
    page.get_by_role("button", name="Verify").click()


def test_verify_shows_verified_on_a_small_start_and_loads_the_literal_papers_violation(browser, app):
    page = open_page(browser, app)
    verify_demo(page, app, "One robot on L1", 3)
    page.get_by_text("Verify: verified:").wait_for(timeout=120_000)
    start = Path(__file__).parent.parent / "demo_patterns"
    app.session.load_robots("vertical-line-4.json", (start / "starts" / "vertical-line-4.json").read_bytes())
    app.session.load_pattern("tee-4.json", (start / "tee-4.json").read_bytes())
    app.session.set_algorithm("apf-opaque-grid-literal")
    assert sorted(app.session.config.pattern) == [(0, 1), (1, 0), (1, 1), (2, 1)]  # the tee-4
    app.request_render()
    page.get_by_role("button", name="Verify").click()
    page.get_by_text("Verifying…").wait_for()
    page.get_by_text("Verify: collision").wait_for(timeout=300_000)
    page.get_by_text("Following the trace: event").wait_for()
    wait_for(lambda: app.session.view().trace_position is not None)
    while app.session.step():
        pass
    app.request_render()
    page.get_by_role("heading", name="✖ COLLISION").wait_for()
    shot(page, "verify-violation")
    page.close()


def test_compare_draws_two_runs_side_by_side_and_names_the_first_differing_decision(browser, app):
    from apf_viz.core.schedule import schedule_of_trace, schedule_text

    demos = Path(__file__).parent.parent / "demo_patterns"
    app.session.load_robots("line.json", (demos / "starts" / "vertical-line-4.json").read_bytes())
    app.session.load_pattern("tee.json", (demos / "tee-4.json").read_bytes())
    _, events = load_trace(demos / "traces" / "literal-collision-4.jsonl")
    app.session.load_schedule("cex.jsonl", schedule_text(4, schedule_of_trace(events, False)).encode())
    app.request_render()
    page = open_page(browser, app)
    open_folder(page, "Compare")
    page.get_by_role("button", name="Compare", exact=True).click()
    page.get_by_text("B apf-opaque-grid-literal").wait_for()
    step = page.get_by_role("button", name="Step")
    for n in range(1, 42):
        step.click()
        wait_for(lambda n=n: app.session.engine.step_index == n)
    # Where the decisions first differ, by a diff of the two runs' events made here (robot, rule, move).
    twin = app.session.screen.twin.engine
    pairs = zip(app.session.engine.history.events(), twin.history.events(), strict=False)
    first = next(
        n
        for n, (a, b) in enumerate(pairs, 1)
        if a.phase == "compute" and (a.rule_id, a.move, a.light) != (b.rule_id, b.move, b.light)
    )
    page.get_by_text(f"First differing decision at event {first}, robot").wait_for()
    page.get_by_text("Its consequence: A robot").wait_for()
    page.get_by_text("apf-opaque-grid-literal: COLLISION").wait_for()
    a, b = app.renderer, app.pair.second
    assert b is not None and b.origin[0] < a.origin[0]  # B is drawn to the right of A
    titles = [h.text for n, h in b.nodes().items() if n.startswith("/title/") and h.visible]
    assert titles == ["B: the paper as written · COLLISION"]  # in words a room reads
    page.get_by_role("button", name="Frame run").click()
    shot(page, "compare")
    page.get_by_role("button", name="Stop comparing").click()
    wait_for(lambda: app.pair.second is None)
    page.close()


def test_two_browsers_select_apart_until_one_follows_the_presenter(browser, app):
    """A laptop's click never changes the projector, and the projector (or anyone) may follow the
    presenter's selection. The first browser to connect presents."""
    for _ in range(12):
        app.session.step()
    projector = open_page(browser, app)
    wait_for(lambda: len(app.screens) == 1)
    laptop = open_page(browser, app)
    wait_for(lambda: len(app.screens) == 2)
    ids = list(app.screens)
    a = next(i for i in ids if app.classroom.is_presenter(i))
    b = next(i for i in ids if i != a)
    x, y = screen_of(app, projector, app.session.engine.current_points()[4])
    projector.mouse.click(x, y)
    wait_for(lambda: app.session.view(app.classroom.state(a)).selected == 4)
    projector.get_by_text("Robot 4 —").first.wait_for()
    rays = app.screens[b].selection.nodes().get("/rays")
    assert app.session.view(app.classroom.state(b)).selected is None and (rays is None or not rays.visible)
    laptop.get_by_text("Click a robot to see what it sees").first.wait_for()
    shot(laptop, "laptop-unchanged-by-the-projector")
    laptop.get_by_label("Follow presenter").check()
    wait_for(lambda: app.session.view(app.classroom.state(b)).selected == 4)
    laptop.get_by_text("Following the presenter's selection.").wait_for()
    laptop.get_by_text("Robot 4 —").first.wait_for()
    wait_for(lambda: app.screens[b].selection.nodes().get("/rays") is not None)
    wait_for(lambda: app.screens[b].selection.nodes()["/rays"].visible)
    shot(laptop, "laptop-follows-the-projector")
    assert not projector.get_by_label("Follow presenter").is_visible()  # the presenter follows nobody


def test_a_camera_moved_by_hand_is_that_browsers_own_until_frame_run(browser, app):
    page = open_page(browser, app)
    wait_for(lambda: len(app.screens) == 1)
    (screen,) = app.screens.values()
    assert screen.state.camera == "framed"
    box = page.locator("canvas").first.bounding_box()
    cx, cy = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    page.mouse.move(cx, cy)
    page.mouse.down(button="right")  # pan
    page.mouse.move(cx + 150, cy + 80, steps=8)
    page.mouse.up(button="right")
    wait_for(lambda: screen.state.camera == "moved")
    page.get_by_role("button", name="Frame run").click()
    wait_for(lambda: screen.state.camera == "framed")
    wait_for(lambda: screen._acknowledged)  # the browser reports the framed pose back: still framed
    assert screen.state.camera == "framed"


def inside_canvas(app: App, page, client_id, cells, caption_room: float = 0.0) -> list:
    """The cells a browser's own camera (as it is now) projects outside its canvas, half a cell of
    margin included: robots and targets must be whole (``caption_room``: a share of the canvas's height
    at its bottom that must stay free, presentation mode's caption)."""
    camera = app.screens[client_id].client.camera
    p, target = np.array(camera.position, dtype=float), np.array(camera.look_at, dtype=float)
    f = (target - p) / np.linalg.norm(target - p)
    r = np.cross(f, [0.0, 0.0, 1.0])
    r /= np.linalg.norm(r)
    u = np.cross(r, f)
    box = page.locator("canvas").first.bounding_box()
    t = np.tan(float(camera.fov) / 2)
    out = []
    for cell in cells:
        x, y = app.renderer.to_scene(cell)
        for dx, dy in ((-0.5, -0.5), (0.5, 0.5)):
            d = np.array([x + dx, y + dy, 0.0]) - p
            ndc_x = (d @ r) / ((d @ f) * t * (box["width"] / box["height"]))
            ndc_y = (d @ u) / ((d @ f) * t)
            if not (-1 <= ndc_x <= 1 and -1 + 2 * caption_room <= ndc_y <= 1):
                out.append(cell)
    return out


def test_the_heart_lecture_stop_by_stop_at_1024x768_in_presentation_mode(browser, app):
    """The issue's walk-through: PageDown from the start to FORMED, each stop one of the paper's stages,
    named in the caption, with the whole run in view below it (screenshots: test-output/lecture-*)."""
    from apf_viz.ui.panels.presentation import CAPTION_ROOM
    from apf_viz.workbench.view_model.legend import symbol_html

    played = demo_session()
    while played.step():
        pass
    stops = [at for at, _ in played.run.stages.marks(played.engine.history, played.engine.history.length)]
    page, cid, screen = projector_page(browser, app)
    page.keyboard.press("p")
    wait_for(lambda: screen.panels.presenting)
    for i, at in enumerate(stops):
        page.keyboard.press("PageDown")
        wait_for(lambda at=at: app.session.engine.step_index == at)
        stage = app.session.view().stage
        caption = screen.panels.presentation.html
        wait_for(lambda stage=stage, caption=caption: symbol_html(stage) in caption.content)
        settled(app, screen)
        cells = [r.position for r in app.session.view().robots] + list(app.session.view().targets)
        assert inside_canvas(app, page, cid, cells, CAPTION_ROOM) == [], (i, stage)
        assert page.locator(".mantine-Notification-root").filter(has_text="Stage").count() == 0
        shot(page, f"lecture-stop-{i:02d}")
    assert app.session.engine.outcome == "formed"
    assert "Formed: every robot is done" in screen.panels.presentation.html.content
    page.close()


@pytest.mark.parametrize("size", [(1400, 900), (1024, 768)])
def test_a_camera_nobody_moved_keeps_the_whole_run_in_view_to_formed(browser, app, size):
    page = browser.new_page(viewport={"width": size[0], "height": size[1]})
    page.set_default_timeout(60_000)
    page.goto(app.addresses[0])  # the presenter address
    page.get_by_label("Event").wait_for()
    wait_for(lambda: len(app.screens) == 1)
    (cid,) = app.screens
    stops = []
    while app.session.step():
        v = app.session.view()
        if v.event in (60, 300, 540) or app.session.engine.finished:
            settled(app, app.screens[cid])  # a frame, and the camera where it was sent
            cells = [r.position for r in app.session.view().robots] + list(app.session.view().targets)
            stops.append((v.event, inside_canvas(app, page, cid, cells)))
    assert app.session.engine.outcome == "formed"
    shot(page, f"formed-in-view-{size[0]}x{size[1]}")
    assert all(not outside for _, outside in stops), stops
    page.close()


def test_after_play_pauses_the_camera_frames_the_run_again(browser, app):
    """Found at the back of a room: Play grew the framing with room to spare, and after a pause the
    robots stayed drawn at 60 % of their size. Paused, a camera that follows the run frames it tightly
    again (the run's own box, not the grown one)."""
    page, cid, screen = projector_page(browser, app)
    page.wait_for_function("document.activeElement === document.body")
    s = app.session
    s.set_speed(400)
    page.keyboard.press("Space")
    wait_for(lambda: s.engine.state.events > 250)
    page.keyboard.press("Space")
    wait_for(lambda: not s.playing)
    settled(app, screen)
    wait_for(lambda: screen.state.framed_bounds == app.renderer.bounds)
    assert screen.state.camera == "framed"
    cells = [r.position for r in s.view().robots] + list(s.view().targets)
    assert not inside_canvas(app, page, cid, cells)  # the whole run in view
    shot(page, "paused-framed-again")
    page.close()


def test_at_1024x768_step_event_last_event_and_why_show_together(browser, app):
    for _ in range(20):
        app.session.step()
    app.session.selected = next(r for r in range(10) if app.session.engine.state.decided[r] is not None)
    app.request_render()
    page = browser.new_page(viewport={"width": 1024, "height": 768})
    page.set_default_timeout(60_000)
    page.goto(app.addresses[0])  # the presenter address
    page.get_by_label("Event").wait_for()
    drawn_there(app, page)
    r = app.session.selected
    for locator in (
        page.get_by_role("button", name="Step"),
        page.get_by_label("Event"),
        page.locator("p", has_text="Last event:").first,
        page.get_by_text(f"Robot {r} · rule").first,
    ):
        box = locator.bounding_box()
        assert box is not None and box["y"] >= 0 and box["y"] + box["height"] <= 768, (locator, box)
    last = page.locator("p", has_text="Last event:").first.inner_text()
    assert last.endswith(app.session.view().last_events[0])  # in full, not cut
    shot(page, "lecture-first-screen-1024x768")
    page.close()


def test_an_upload_in_one_browser_is_told_to_that_browser_only(browser, app, tmp_path):
    a = open_page(browser, app)
    b = open_page(browser, app)
    pattern = tmp_path / "heart-again.json"
    pattern.write_text((Path(__file__).parent.parent / "demo_patterns" / "heart.json").read_text())
    open_folder(a, "Files")
    with a.expect_file_chooser() as chooser:
        a.get_by_role("button", name="Upload pattern").click()
    chooser.value.set_files(str(pattern))
    a.get_by_text("heart-again.json").first.wait_for()  # the uploading browser sees its toast
    time.sleep(1.5)
    assert b.get_by_text("Uploading").count() == 0 and b.get_by_text("heart-again.json").count() == 0
    a.close()
    b.close()


def test_panels_follow_the_run_verdict_variant_and_banner(browser, app):
    page = open_page(browser, app)
    verify_demo(page, app, "One robot on L1", 3)
    page.get_by_text("Verify: ").first.wait_for(timeout=120_000)
    page.get_by_role("combobox", name="Demo").click()
    page.get_by_role("option", name="Heart from 10 robots").click()
    wait_for(lambda: app.session.engine.k == 10)
    wait_for(lambda: page.get_by_text("Verify: ").count() == 0)  # the verdict was about the other start
    open_folder(page, "Algorithm")
    page.get_by_role("combobox", name="Algorithm").click()
    page.get_by_role("option", name="apf-opaque-grid-literal").click()
    wait_for(lambda: app.session.algorithm_name == "apf-opaque-grid-literal")
    variant = page.locator("xpath=//*[text()='Variant']/following::input[1]")
    wait_for(lambda: variant.input_value() == "apf-opaque-grid-literal")  # follows the dropdown too
    app.session.set_algorithm("apf-opaque-grid")
    while app.session.step():
        pass
    app.request_render()
    page.get_by_role("heading", name="FORMED").wait_for()
    open_folder(page, "Edit")
    page.get_by_role("combobox", name="Mode").click()
    page.get_by_role("option", name="Edit pattern").click()
    wait_for(lambda: app.session.mode == "edit-pattern")
    wait_for(lambda: page.get_by_role("heading", name="FORMED").count() == 0)  # no banner while editing
    page.close()


def test_a_lecture_runs_from_the_keyboard(browser, app):
    page = open_page(browser, app)
    page.keyboard.press("Enter")
    wait_for(lambda: app.session.engine.step_index == 1)
    page.keyboard.press("Enter")
    wait_for(lambda: app.session.engine.step_index == 2)
    page.keyboard.press("Backspace")
    wait_for(lambda: app.session.engine.step_index == 1)
    page.keyboard.press("Space")
    wait_for(lambda: app.session.playing)
    page.keyboard.press("Space")
    wait_for(lambda: not app.session.playing)
    first = app.session.view().stage
    page.keyboard.press("PageDown")
    wait_for(lambda: app.session.view().stage != first)
    second, at = app.session.view().stage, app.session.engine.step_index
    page.keyboard.press("PageDown")
    wait_for(lambda: app.session.view().stage not in (first, second))
    page.keyboard.press("PageUp")  # back to where the second stage began
    wait_for(lambda: app.session.engine.step_index == at)
    assert app.session.view().stage == second
    (screen,) = [x for x in app.screens.values()]
    assert screen.state.camera == "framed"  # the keys drove the run, not the camera
    for _ in range(5):  # each PageDown's message replaces the last: one on the canvas, not five
        page.keyboard.press("PageDown")
        time.sleep(0.3)
    wait_for(lambda: page.locator(".mantine-Notification-root").count() == 1)
    # A Demo picked from the panel's dropdown, then the keys again, without a click on the canvas.
    page.get_by_role("combobox", name="Demo").click()
    page.get_by_role("option", name="Robots already on K").click()
    wait_for(lambda: app.session.engine.step_index == 0 and "K" in app.session.view().scenario_note)
    wait_for(lambda: page.evaluate("document.activeElement === document.body"))  # the panel let go
    page.keyboard.press("Enter")
    wait_for(lambda: app.session.engine.step_index == 1)
    page.close()


def test_presentation_mode_collapses_the_panel_and_narrates_on_the_canvas(browser, app):
    page = browser.new_page(viewport={"width": 1024, "height": 768})
    page.set_default_timeout(60_000)
    page.goto(app.addresses[0])  # the presenter address
    page.get_by_label("Event").wait_for()
    other = open_page(browser, app)  # a second browser keeps its panel
    time.sleep(1.0)
    page.keyboard.press("P")
    page.get_by_text("Phase 1: leader election").first.wait_for()
    for _ in range(3):
        page.keyboard.press("Enter")
    wait_for(lambda: app.session.engine.step_index == 3)
    last = app.session.view().last_events[0]
    page.get_by_text(f"Event 3 · {last}").wait_for()
    shot(page, "presentation-1024x768")
    page.get_by_role("button", name="Step").wait_for(state="hidden")  # the panel collapses (a frame later)
    assert other.get_by_role("button", name="Step").is_visible()  # only in the browser that asked
    page.keyboard.press("P")
    page.get_by_role("button", name="Step").wait_for(state="visible")
    page.close()
    other.close()


def test_go_to_the_fatal_decision_of_a_collision(browser, app):
    app.session.load_scenario("The literal paper collides")
    while app.session.step():
        pass
    app.request_render()
    computed = app.session.view().fatal[1]
    page = open_page(browser, app)
    page.get_by_text("decided this move at step").first.wait_for()
    shot(page, "collision-explained")
    page.get_by_role("button", name="Go to the fatal decision").click()
    wait_for(lambda: app.session.engine.step_index == computed)
    wait_for(lambda: "· Compute" in page.locator("p", has_text="Last event:").first.inner_text())
    page.close()


def test_the_paper_panel_highlights_the_line_of_a_phase_2_decision_beside_the_canvas(browser, app):
    """At 1024×768: the demo stepped to a Phase 2 decision; the Paper folder shows Algorithm 2 with that
    decision's line highlighted, in view beside the canvas (screenshot: test-output/paper-phase2)."""
    s = app.session
    while not (s.view().paper_decision or (0, ""))[1].startswith("A2."):
        assert s.step()
    robot, rule = s.view().paper_decision
    paper = s.engine.algorithm.pseudocode()
    (key,) = paper.lines_of(rule)[:1]
    block, i = paper.line(key)
    page = browser.new_page(viewport={"width": 1024, "height": 768})
    page.set_default_timeout(60_000)
    page.goto(app.addresses[0])  # the presenter address
    page.get_by_label("Event").wait_for()
    page.get_by_text(f"Robot {robot}: {rule}").wait_for()
    hit = page.locator("[data-hit]").first
    hit.scroll_into_view_if_needed()
    assert "Algorithm 2" in page.locator("b", has_text="Algorithm 2").first.inner_text()
    box, canvas = hit.bounding_box(), page.locator("canvas").first.bounding_box()
    assert box["y"] >= 0 and box["y"] + box["height"] <= 768  # the highlighted line on screen …
    assert canvas["width"] > 500 and canvas["x"] + canvas["width"] <= box["x"] + 5  # … beside the canvas
    assert block.lines[i].text.split(" ")[0] in hit.inner_text()
    shot(page, "paper-phase2")
    page.close()


def test_export_lecture_downloads_every_stop_as_a_slide_and_a_page(browser, app):
    import io
    import zipfile

    from apf_viz.lecture import lectures

    lecture = lectures()["Where the paper breaks under ASYNC"]
    page = open_page(browser, app)
    page.get_by_role("combobox", name="Lecture").click()
    page.get_by_role("option", name=lecture.title).click()
    wait_for(lambda: app.session.screen.lecture is not None)
    (screen,) = app.screens.values()
    wait_for(lambda: screen.panels.presenting)  # a lecture opens in presentation mode: P for the panel
    page.wait_for_function("document.activeElement === document.body")
    page.keyboard.press("p")
    wait_for(lambda: not screen.panels.presenting)
    open_folder(page, "Files")
    with page.expect_download(timeout=120_000) as download:
        page.get_by_role("button", name="Export lecture").click()
    archive = zipfile.ZipFile(io.BytesIO(Path(download.value.path()).read_bytes()))
    names = sorted(archive.namelist())
    assert names == sorted(["index.html", *(f"stop-{i:02d}.png" for i in range(1, len(lecture.stops) + 1))])
    index = archive.read("index.html").decode()
    assert all(html.escape(stop.title) in index for stop in lecture.stops)
    slide = iio.imread(archive.read("stop-02.png"), extension=".png")
    legend = slide[:, int(slide.shape[1] * 0.74) :].astype(np.int32)  # the legend beside the picture
    for light in ("off", "leader"):
        color = np.array(app.session.view().legend[light].color)
        assert (np.abs(legend - color).max(axis=2) <= 2).sum() > 20, light
    (OUT / "lecture-export-stop-02.png").write_bytes(archive.read("stop-02.png"))
    assert app.session.lecturer.position == 0  # back where the lecture stood
    page.close()


def offline_context(browser, allowed: tuple[str, ...] = ("file:",)):
    """A 1024×768 browser context that loads only URLs starting with ``allowed`` (a page read from
    disk, with no network): (the context, the list of URLs it refused)."""
    context = browser.new_context(viewport={"width": 1024, "height": 768})
    refused: list[str] = []

    def route(request_route):
        if request_route.request.url.startswith(allowed):
            request_route.continue_()
        else:
            refused.append(request_route.request.url)
            request_route.abort()

    context.route("**/*", route)
    return context, refused


def blank_drawing(browser, app: App, tool: str):
    """A 1024×768 page in Edit pattern with the pattern cleared and ``tool`` chosen: (the page, its
    client id, its screen)."""
    s = app.session
    page, cid, screen = projector_page(browser, app)
    open_folder(page, "Edit")
    _choose(page, "Mode", "Edit pattern")
    wait_for(lambda: s.mode == "edit-pattern")
    page.get_by_role("button", name="Clear pattern").click()
    wait_for(lambda: s.editor.pattern == [])
    _choose(page, "Tool", tool)
    wait_for(lambda: s.screen.studio.tool == tool)
    return page, cid, screen


def _choose(page, label: str, option: str, tries: int = 4) -> None:
    """Choose ``option`` in the dropdown ``label`` until the page shows it chosen: on a loaded machine (the
    whole suite, four workers on two cores) an option was clicked while its list was still opening, and the
    choice never happened."""
    from playwright.sync_api import TimeoutError as PlaywrightTimeout

    box = page.get_by_role("combobox", name=label)
    for _ in range(tries):
        box.click()
        item = page.get_by_role("option", name=option, exact=True)
        try:  # the list may be drawn again (the server refreshing the panel) under the pointer: try again
            item.wait_for(state="visible", timeout=20_000)
            item.click(timeout=20_000)
        except PlaywrightTimeout:
            page.keyboard.press("Escape")
            continue
        end = time.time() + 10
        while time.time() < end:
            if box.input_value() == option:
                return
            time.sleep(0.1)
        page.keyboard.press("Escape")
    raise AssertionError(f"the dropdown {label!r} never showed {option!r}")


def chosen(page, label: str, option: str, done, tries: int = 3) -> None:
    """:func:`_choose` until ``done()``: on a loaded machine (the whole suite, four workers on two cores)
    a dropdown's option was once clicked while its list was still opening, and the choice never sent."""
    for _ in range(tries - 1):
        _choose(page, label, option)
        try:
            wait_for(done, timeout=15)
            return
        except AssertionError:
            page.keyboard.press("Escape")
    _choose(page, label, option)
    wait_for(done)


def _drag(page, app, a, b, modifier: str | None = None) -> None:
    """A drag on the canvas from the middle of cell ``a`` to the middle of cell ``b``."""
    (x0, y0), (x1, y1) = screen_of(app, page, a), screen_of(app, page, b)
    if modifier:
        page.keyboard.down(modifier)
    page.mouse.move(x0, y0)
    page.mouse.down()
    for i in range(1, 11):
        page.mouse.move(x0 + (x1 - x0) * i / 10, y0 + (y1 - y0) * i / 10)
        time.sleep(0.02)
    page.mouse.up()
    if modifier:
        page.keyboard.up(modifier)


def test_the_pattern_studio_by_gestures_then_played_to_formed(browser, app):
    """At 1024×768: a 6×4 box by one drag, a Shift-drag erase, "HI" in two actions, undo ×2, then a
    pattern of the robots' size played to FORMED with every robot on a drawn target."""
    s = app.session
    page, cid, screen = blank_drawing(browser, app, "box")
    time.sleep(0.5)
    _drag(page, app, (9, 0), (14, 3))  # beside the robots, in view
    wait_for(lambda: len(s.editor.pattern) == 24)
    assert set(s.editor.pattern) == {(x, y) for x in range(9, 15) for y in range(4)}
    shot(page, "studio-box")
    _drag(page, app, (10, 1), (11, 2), modifier="Shift")
    wait_for(lambda: len(s.editor.pattern) == 20)
    _choose(page, "Tool", "text")
    find = "Array.from(document.querySelectorAll('input')).find(e => e.value === 'APF')"
    page.wait_for_function(f"!!({find})")  # viser's text field has no label a locator finds: by its value
    text_id = page.evaluate(f"({find}).id")
    page.locator(f"#{text_id}").fill("HI")  # action 1: the word …
    page.locator(f"#{text_id}").press("Enter")
    wait_for(lambda: s.screen.studio.text == "HI")
    x, y = screen_of(app, page, (9, 9))
    page.mouse.click(x, y)  # … action 2: where it goes
    wait_for(lambda: len(s.editor.pattern) == 20 + len(shapes.text("HI", (0, 0))))
    shot(page, "studio-text")
    page.keyboard.press("Control+z")
    wait_for(lambda: len(s.editor.pattern) == 20)
    page.get_by_role("button", name="Undo").click()
    wait_for(lambda: len(s.editor.pattern) == 24)  # undo ×2: the box whole again
    # 24 cells for 10 robots: what each fit would do is said before either is clicked.
    page.get_by_text("Fit pattern trims the 14 last-drawn cells · Fit robots adds 14 robots").wait_for()
    page.get_by_role("button", name="Fit robots").click()  # 14 robots placed beside the 10
    wait_for(lambda: len(s.editor.robots) == 24)
    drawn = set(s.editor.pattern)
    _choose(page, "Mode", "Run")
    wait_for(lambda: s.mode == "run")
    while s.step():
        pass
    assert s.engine.outcome == "formed"
    formed = {r.position for r in s.view().robots}
    assert s.engine.pattern == tuple(s.config.pattern) and len(formed) == len(drawn)
    from apf_viz.core.pattern_match import matches_pattern

    assert matches_pattern(list(formed), list(drawn))  # every robot on a drawn target (up to placement)
    drawn_there(app, page)
    shot(page, "studio-formed")
    page.close()


def test_a_slow_drag_and_a_click_paint_exactly_their_cells_and_the_camera_never_moves(browser, app):
    """At 1024×768, as a designer draws: a slow drag up five cells paints those five and no other, a click
    paints its cell, the camera stays exactly where it was and the grid keeps a line per cell; E picks the
    eraser without lifting the camera; U the box, which takes both end rows though released short of the
    last cell's centre; a choice in a dropdown gives the keys back to the canvas."""
    s = app.session
    page, cid, screen = blank_drawing(browser, app, "cell")
    drawn_there(app, page)
    wait_for(lambda: screen._reported is not None)  # the page has reported where its camera is
    time.sleep(1.0)  # and any pose sent before has arrived
    before = np.asarray(screen.client.camera.position, dtype=float).copy()

    def camera_kept() -> bool:
        return bool(np.abs(np.asarray(screen.client.camera.position, dtype=float) - before).max() < 1e-6)

    (x0, y0), (x1, y1) = screen_of(app, page, (9, 0)), screen_of(app, page, (9, 4))
    page.mouse.move(x0, y0)
    page.mouse.down()
    for i in range(1, 41):  # slowly: about two seconds for five cells
        page.mouse.move(x0 + (x1 - x0) * i / 40, y0 + (y1 - y0) * i / 40)
        time.sleep(0.05)
    page.mouse.up()
    wait_for(lambda: len(s.editor.pattern) >= 5)
    time.sleep(1.0)  # any re-frame would have reached the page by now
    assert set(s.editor.pattern) == {(9, y) for y in range(5)}
    x, y = screen_of(app, page, (12, 2))
    page.mouse.click(x, y)
    wait_for(lambda: (12, 2) in s.editor.pattern)
    drawn_there(app, page)
    assert set(s.editor.pattern) == {(9, y) for y in range(5)} | {(12, 2)}
    assert camera_kept() and screen.state.camera == "framed"
    assert app.renderer.nodes()["/grid/cells"].visible  # a line per cell, as before the stroke
    shot(page, "studio-slow-drag")
    page.keyboard.press("e")
    wait_for(lambda: s.screen.studio.tool == "eraser")
    page.get_by_text("E eraser").first.wait_for()  # the keys line says it
    time.sleep(0.5)
    assert camera_kept()  # E is viser's camera lift in Run, not while drawing
    page.keyboard.press("u")
    wait_for(lambda: s.screen.studio.tool == "box")
    drawn_there(app, page)
    _drag(page, app, (14, 0), (15.7, 1.7))  # released short of (16, 2)'s centre
    wait_for(lambda: len(s.editor.pattern) == 6 + 9)
    assert {(x, y) for x in range(14, 17) for y in range(3)} <= set(s.editor.pattern)
    _choose(page, "Mirror", "x ↔")
    wait_for(lambda: s.screen.studio.mirror == "x ↔")
    wait_for(lambda: page.evaluate("document.activeElement === document.body"))
    page.keyboard.press("g")  # a key, not a letter typed into the dropdown
    wait_for(lambda: s.screen.studio.tool == "fill")
    assert camera_kept()
    page.close()


def test_in_edit_robots_a_robot_moves_with_the_move_tool(browser, app):
    s = app.session
    page = open_page(browser, app, {"width": 1024, "height": 768})
    open_folder(page, "Edit")
    _choose(page, "Mode", "Edit robots")
    wait_for(lambda: s.mode == "edit-robots")
    _choose(page, "Tool", "move")
    wait_for(lambda: s.screen.studio.tool == "move")
    start = s.editor.robots[0]
    free = (start[0], start[1] - 2)
    while free in s.editor.robots:
        free = (free[0], free[1] - 1)
    x, y = screen_of(app, page, start)
    page.mouse.click(x, y)
    # The first click is seen to wait for the second: the panel says so, the cell is marked.
    page.get_by_text(f"first click at {start}").wait_for()
    page.get_by_text("where it goes").first.wait_for()
    wait_for(lambda: app.renderer.nodes()["/anchor"].visible)
    shot(page, "studio-move-first-click")
    x, y = screen_of(app, page, free)
    page.mouse.click(x, y)
    wait_for(lambda: free in s.editor.robots and start not in s.editor.robots)
    assert len(s.editor.robots) == s.engine.k
    wait_for(lambda: not app.renderer.nodes()["/anchor"].visible)
    shot(page, "studio-move-robot")
    page.close()


def test_back_to_run_from_the_mode_dropdown_gives_the_keys_back_to_the_run(browser, app):
    """Mode → Run in the Edit folder: the dropdown lets go of the keyboard (as the Demo's does), so Space
    plays the run instead of opening the dropdown again."""
    page = open_page(browser, app, {"width": 1024, "height": 768})
    open_folder(page, "Edit")
    choose_mode(page, app, "Edit pattern", "edit-pattern")
    choose_mode(page, app, "Run", "run")
    wait_for(lambda: page.evaluate("document.activeElement === document.body"))
    page.keyboard.press("Space")
    wait_for(lambda: app.session.playing)
    page.keyboard.press("Space")
    wait_for(lambda: not app.session.playing)
    page.close()


def test_a_demo_picked_over_a_drawing_says_where_the_drawing_went_and_undo_brings_it_back(browser, app):
    page = open_page(browser, app, {"width": 1024, "height": 768})
    open_folder(page, "Edit")
    choose_mode(page, app, "Edit pattern", "edit-pattern")
    page.get_by_role("button", name="Clear pattern").click()
    wait_for(lambda: not app.session.editor.pattern)
    for cell in [(20, 0), (21, 0), (22, 0)]:  # drawn by clicks (the studio test draws with the mouse)
        app.session.click(cell)
    drawn = list(app.session.editor.pattern)
    page.get_by_role("combobox", name="Demo").click()
    page.get_by_role("option", name="One robot on L1").click()
    page.get_by_text("Undo brings it back").wait_for()
    shot(page, "demo-over-a-drawing")
    choose_mode(page, app, "Edit pattern", "edit-pattern")
    page.get_by_role("button", name="Undo").click()
    wait_for(lambda: app.session.editor.pattern == drawn)
    page.close()


def choose_mode(page, app: App, label: str, mode: str) -> None:
    """The Edit folder's Mode dropdown (the folder open), as a person picks it: again if the choice was
    lost (:func:`chosen`; the suite once clicked the option while the list was still opening)."""
    chosen(page, "Mode", label, lambda: app.session.mode == mode)


def test_a_counterexample_stuck_before_any_event_opens_as_stuck(browser):
    """The light lab's call=off trace ends where it starts (every robot off, which shows call, waits for
    ever): opened in the visualiser at 1024×768 it reads as stuck, not as a run that has not begun."""
    trace = (
        Path(__file__).resolve().parent.parent
        / "demo_patterns/traces/lights/apf-opaque-grid+merge(call=off).jsonl"
    )
    session = demo_session()
    session.load_trace(trace.name, trace.read_bytes())
    a = App(session, port=free_port(), verbose=False)
    try:
        page = open_page(browser, a, {"width": 1024, "height": 768})
        page.get_by_role("heading", name="⊘ STUCK").wait_for()
        assert a.session.engine.outcome == "stuck" and a.session.engine.step_index == 0
        shot(page, "lights-call-off-stuck")
        page.close()
    finally:
        a.stop()


def test_escape_gives_the_keys_back_from_a_panel_field(browser, app):
    """A field with focus keeps the keys (viser ignores its hotkeys then): Escape hands them back, and
    Enter steps the run again."""
    page = open_page(browser, app)
    field = page.locator("input[type=text]:not([disabled]):not([id^=mantine])").first  # a value field
    field.focus()
    page.keyboard.press("Enter")
    time.sleep(0.5)
    assert app.session.view().steps == 0 and field.evaluate("e => e === document.activeElement")  # its key
    page.keyboard.press("Escape")
    page.wait_for_function("document.activeElement === document.body")
    page.keyboard.press("Enter")
    wait_for(lambda: app.session.view().steps == 1)
    page.close()


def test_a_class_page_that_connects_first_follows_and_only_the_presenter_drives(browser, app):
    """The roles come from the address, not the order: a class page opened first follows; its keys and
    buttons change nothing shared; the presenter's do and the class page shows them; "Class may drive"
    hands the class the run, and unticking takes it back; a reloaded presenter page presents again."""
    presenter_address, class_address = app.addresses
    follower = browser.new_page(viewport=VIEWPORT)
    follower.set_default_timeout(60_000)
    follower.goto(class_address)
    follower.get_by_label("Event").wait_for()
    wait_for(lambda: len(app.screens) == 1)
    presenter = open_page(browser, app)
    wait_for(lambda: len(app.screens) == 2)
    assert sorted(s.state.role for s in app.screens.values()) == ["class", "presenter"]
    follower.get_by_text("Following the lecture").first.wait_for()
    presenter.get_by_text("Presenting").first.wait_for()
    assert not follower.get_by_role("button", name="Step").is_visible()  # its controls are absent
    follower.get_by_role("button", name="Frame run").wait_for()  # its own camera's stays
    assert not follower.get_by_role("button", name="Next move").is_visible()
    follower.get_by_text("the presenter's keys drive the run").first.wait_for()  # and its keys say so
    for key in ("Enter", " ", "PageDown", "Backspace", "m"):
        follower.keyboard.press(key)
        time.sleep(0.3)
    time.sleep(1.0)
    assert app.session.engine.step_index == 0 and not app.session.playing  # nothing shared changed
    follower.get_by_text("this page follows the lecture").first.wait_for()  # and it was told why
    follower.keyboard.press("p")  # presentation mode: the panel folds, and the caption says what it is
    follower.get_by_text("Following the lecture · I: details, and the keys").wait_for()
    follower.keyboard.press("i")  # the details name its keys
    follower.get_by_text("the presenter's keys drive the run · P the panel").wait_for()
    follower.keyboard.press("i")
    presenter.keyboard.press("p")
    presenter.get_by_text("Presenting · I: details, and the keys").wait_for()
    follower.keyboard.press("p")
    presenter.keyboard.press("p")
    presenter.keyboard.press("Enter")
    wait_for(lambda: app.session.engine.step_index == 1)
    wait_for(lambda: event_value(follower) == 1)  # the class page follows the run
    presenter.get_by_label("Class may drive").check()
    wait_for(lambda: app.classroom.class_may_drive)
    follower.get_by_role("button", name="Step").wait_for()  # the class now has the controls
    follower.keyboard.press("Enter")
    wait_for(lambda: app.session.engine.step_index == 2)
    follower.get_by_role("button", name="Next move").wait_for()
    presenter.get_by_label("Class may drive").uncheck()
    wait_for(lambda: not app.classroom.class_may_drive)
    follower.get_by_role("button", name="Step").wait_for(state="hidden")
    follower.get_by_role("button", name="Next move").wait_for(state="hidden")
    time.sleep(1.0)  # the checkbox gave the keys back: Space plays, and does not tick it again
    presenter.keyboard.press(" ")
    wait_for(lambda: app.session.playing)
    presenter.keyboard.press(" ")
    wait_for(lambda: not app.session.playing)
    assert not app.classroom.class_may_drive
    app.session.seek(2)
    app.request_render()
    follower.keyboard.press("Enter")
    time.sleep(1.0)
    assert app.session.engine.step_index == 2  # taken back
    shot(follower, "class-page-following")
    presenter.reload()
    presenter.get_by_text("Presenting").first.wait_for()
    wait_for(lambda: sorted(s.state.role for s in app.screens.values()) == ["class", "presenter"])
    presenter.keyboard.press("Enter")
    wait_for(lambda: app.session.engine.step_index == 3)
    follower.close()
    presenter.close()


def _canvas(page) -> np.ndarray:
    png = page.locator("canvas").first.screenshot()
    return np.asarray(Image.open(BytesIO(png)).convert("RGB"), dtype=np.int32)


def test_a_class_page_tries_it_itself_while_the_projector_is_untouched_and_comes_back(browser, app):
    """Try it yourself: the class page branches a run of its own from the lecture's as it is; its keys
    step that run alone (the shared run and the projector do not move), the presenter's moves reach
    neither its run nor its scene (the shared run's root hidden there), and Back to the lecture follows
    again."""
    presenter_address, class_address = app.addresses
    presenter = open_page(browser, app)
    student = browser.new_page(viewport=VIEWPORT)
    student.set_default_timeout(60_000)
    student.goto(class_address)
    student.get_by_label("Event").wait_for()
    wait_for(lambda: len(app.screens) == 2)
    for _ in range(5):
        presenter.keyboard.press("Enter")
    wait_for(lambda: app.session.engine.step_index == 5)
    wait_for(lambda: event_value(student) == 5)
    student.get_by_role("button", name="Try it yourself").click()
    student.get_by_text("Your own run").first.wait_for()
    page = next(x for x in app.screens.values() if x.state.role == "class")
    assert page.own is not None and page.session is not app.session and page.page.own is page.session
    student.get_by_role("button", name="Step").wait_for()  # its own run's controls, and not the room's
    assert not student.get_by_role("button", name="Verify").is_visible()
    assert not student.get_by_label("Lecture").is_visible()
    for _ in range(3):
        student.keyboard.press("Enter")
    wait_for(lambda: page.session.engine.step_index == 8)
    wait_for(lambda: event_value(student) == 8)
    assert app.session.engine.step_index == 5 and event_value(presenter) == 5  # the projector untouched
    own = (page.session.engine.step_index, page.session.engine.current_points())
    drawn = []  # the student's own run drawn anew: only when it changed, not each frame of the projector
    render = app.own_runs.render
    app.own_runs.render = lambda screen: (drawn.append(screen.client.client_id), render(screen))
    frames = app.frames
    app.session.run_until("move")  # the presenter's run moves robots …
    app.session.run_until("move")
    app.request_render()
    wait_for(lambda: event_value(presenter) == app.session.engine.step_index)
    time.sleep(1.5)
    # … which reach neither the student's run nor its scene: the shared run's root is hidden there by a
    # frame of the page's own (viser draws a page's own variant of a node before the shared one).
    assert (page.session.engine.step_index, page.session.engine.current_points()) == own
    assert page._hiding and not page._hiding[0].visible and event_value(student) == 8
    assert app.frames > frames and drawn == []
    student.keyboard.press("Enter")  # its own step: drawn anew
    wait_for(lambda: event_value(student) == 9)
    assert drawn and set(drawn) == {page.client.client_id}
    app.own_runs.render = render
    shot(student, "class-page-own-run")
    student.get_by_role("button", name="Back to the lecture").click()
    student.get_by_text("Following the lecture").first.wait_for()
    wait_for(lambda: page.own is None)
    wait_for(lambda: event_value(student) == app.session.engine.step_index)  # following again
    student.get_by_role("button", name="Try it yourself").click()  # again, and then the page leaves:
    wait_for(lambda: len(app.classroom.own_pages()) == 1)
    student.close()
    wait_for(lambda: len(app.screens) == 1 and app.classroom.own_pages() == [])  # its run is dropped
    presenter.close()


def test_tried_at_a_compare_the_students_run_compares_beside_itself(browser, app):
    """A student who tries it at a Compare stop gets both runs in its own scene: its run, and the second
    algorithm's run following it (not the projector's), framed together; back to the lecture, both go."""
    presenter_address, class_address = app.addresses
    presenter = open_page(browser, app, {"width": 1024, "height": 768})
    app.session.compare_with("apf-opaque-grid-literal")
    for _ in range(30):
        presenter.keyboard.press("Enter")
    wait_for(lambda: app.session.engine.step_index == 30)
    student = browser.new_page(viewport={"width": 1024, "height": 768})
    student.set_default_timeout(60_000)
    student.goto(class_address)
    student.get_by_label("Event").wait_for()
    wait_for(lambda: event_value(student) == 30)
    student.get_by_role("button", name="Try it yourself").click()
    page = next(x for x in app.screens.values() if x.state.role == "class")
    wait_for(lambda: page._own_pair is not None and page._own_pair.second is not None)
    second = page._own_pair.second
    assert second.server is page.client and second.root == "/mine"  # in the student's scene alone
    for _ in range(12):
        student.keyboard.press("Enter")
    wait_for(lambda: event_value(student) == 42)
    twin = page.session.screen.twin
    assert twin is not app.session.screen.twin and twin.engine.step_index == 42
    assert app.session.screen.twin.engine.step_index == 30  # the projector's second run stays
    a, b = page.own.bounds, second.bounds
    assert a[0] <= b[0] and b[2] <= a[2]  # the framed box holds both runs
    shot(student, "class-page-own-run-compare")
    student.get_by_role("button", name="Back to the lecture").click()
    wait_for(lambda: page.own is None and page._own_pair is None)
    assert not second.nodes()  # its nodes removed from the student's scene
    student.close()
    presenter.close()


def test_a_class_follows_a_lecture_to_formed_while_one_student_tries_it_alone(browser):
    """The class scenario, end to end: `serve --lecture` with the projector at the presenter address
    (1024×768) and two students at the class address. The presenter pages down; both students follow; one
    leaves presentation mode, tries a run of its own mid-lecture, steps it (the projector does not move),
    and comes back; the presenter goes on to the last stop, FORMED, and both students show it."""
    from apf_viz.lecture import lectures

    lecture = lectures()["The algorithm in 12 stops"]
    session = demo_session()
    session.start_lecture(lecture)
    served = App(session, port=free_port(), verbose=False, present=True)
    try:
        presenter_address, class_address = served.addresses
        projector = browser.new_page(viewport={"width": 1024, "height": 768})
        projector.set_default_timeout(60_000)
        projector.goto(presenter_address)
        projector.get_by_text(lecture.stops[0].title).first.wait_for()
        students = []
        for _ in range(2):
            student = browser.new_page(viewport=VIEWPORT)
            student.set_default_timeout(60_000)
            student.goto(class_address)
            students.append(student)
        wait_for(lambda: len(served.screens) == 3)
        for student in students:  # they open presenting, as the projector: P shows their panel
            student.get_by_text(lecture.stops[0].title).first.wait_for()
            student.keyboard.press("p")
            student.get_by_label("Event").wait_for()
            assert not student.get_by_role("button", name="Next stop").is_visible()  # the presenter's
        for i in range(1, 6):
            projector.keyboard.press("PageDown")
            wait_for(lambda i=i: session.lecturer.position == i)
        at = session.view().event
        for student in students:
            wait_for(lambda student=student: event_value(student) == at)  # both follow
        trying = students[0]
        trying.get_by_role("button", name="Try it yourself").click()
        trying.get_by_text("Your own run").first.wait_for()
        for _ in range(3):
            trying.keyboard.press("Enter")
        page = next(x for x in served.screens.values() if x.own is not None)
        wait_for(lambda: page.session.engine.step_index == session.engine.step_index + 3)
        assert session.view().event == at and session.lecturer.position == 5  # the projector untouched
        shot(trying, "class-scenario-own-run")
        trying.get_by_role("button", name="Back to the lecture").click()
        trying.get_by_text("Following the lecture").first.wait_for()
        for i in range(6, len(lecture.stops)):
            projector.keyboard.press("PageDown")
            wait_for(lambda i=i: session.lecturer.position == i)
        wait_for(lambda: session.engine.outcome == "formed")
        end = session.view().event
        for n, student in enumerate(students):
            wait_for(lambda student=student: event_value(student) == end)
            shot(student, f"class-scenario-student-{n + 1}-formed")
        shot(projector, "class-scenario-projector-formed")
    finally:
        served.stop()
