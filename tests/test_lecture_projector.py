"""Every stop of every shipped lecture on a projector, measured in a real browser (Debian's chromium).

At 1024×768 in presentation mode: the stop's title and words at their sizes, never shrunk, all of them
shown (nothing scrolled out of the caption), the caption within its share of the height, robot numbers
at 14 px or more. At 1024×768 and 1400×900: every label of the scene on its robot (within a cell) and
over no other label. viser draws scene labels in WebGL, not as DOM, so their boxes are measured the way
its label renderer lays them out (viser/client/src/label: a bottom-left anchor, the text's advance and
the font's line height at 12 px × the label's scale, padded by a fifth of the line height), projected
through the page's own camera. Screenshots of every stop: test-output/projector-*.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import pytest

from apf_viz.lecture import lectures
from apf_viz.ui.app import App, demo_session, free_port
from apf_viz.ui.caption_room import CAPTION_ROOM
from apf_viz.ui.scene.style import GHOST_BADGE_OFFSET
from apf_viz.workbench.view_model.caption import TITLE_PX, WORDS_PX
from tests.test_ui_browser import OUT, _canvas, inside_canvas, offline_context, settled, wait_for

playwright = pytest.importorskip("playwright.sync_api")
pytestmark = pytest.mark.browser

LABEL_FONT_STACK = (
    '-apple-system, BlinkMacSystemFont, "Segoe UI", "Roboto", "Helvetica Neue", Arial, sans-serif'
)
SCREEN_EM_PX = 12.0  # viser: a screen-sized label's em at font_screen_scale 1
PADDING = 0.2  # viser: a label's background padding, a share of its line height
NUMBER_PX = 18.0  # the smallest robot number the back row reads: 9 px in a picture at half size

# The caption as the page lays it out: the size of each of its texts, its box and its scrolling.
CAPTION_JS = """() => {
  const title = document.querySelector('[data-apf=title]');
  if (!title) return null;
  const root = title.parentElement;
  let scroller = root;
  const scrolls = e => /(auto|scroll)/.test(getComputedStyle(e).overflowY);
  while (scroller && !scrolls(scroller)) scroller = scroller.parentElement;
  let panel = root;
  const placed = e => ['absolute', 'fixed'].includes(getComputedStyle(e).position);
  while (panel && !placed(panel)) panel = panel.parentElement;
  const sizes = [];
  root.querySelectorAll('*').forEach(e => {
    // A symbol's sub- and superscripts are set smaller than its letter, as in the paper.
    if (e.closest('sub,sup') || e.tagName === 'IMG') return;
    if ([...e.childNodes].some(n => n.nodeType === 3 && n.textContent.trim()))
      sizes.push([parseFloat(getComputedStyle(e).fontSize), e.textContent.slice(0, 40)]);
  });
  const box = panel.getBoundingClientRect();
  return {title: parseFloat(getComputedStyle(title).fontSize),
          say: parseFloat(getComputedStyle(root.querySelector('[data-apf=say]')).fontSize),
          sizes, text: root.innerText,
          scroll: [scroller.scrollHeight, scroller.clientHeight], top: scroller.scrollTop,
          panel: [box.top, box.height]};
}"""

# Notifications over the caption's box (the room reads the caption, not what covers it).
COVERED_JS = """() => {
  const say = document.querySelector('[data-apf=say]');
  if (!say) return [];
  const r = say.parentElement.getBoundingClientRect();
  return [...document.querySelectorAll('.mantine-Notification-root')]
    .filter(n => { const b = n.getBoundingClientRect();
                   return b.left < r.right && b.right > r.left && b.top < r.bottom && b.bottom > r.top; })
    .map(n => n.innerText.slice(0, 60));
}"""

MEASURE_JS = """([texts, font]) => {
  const ctx = document.createElement('canvas').getContext('2d');
  ctx.font = font;
  const probe = ctx.measureText('M');
  return {widths: texts.map(t => ctx.measureText(t).width),
          line: probe.fontBoundingBoxAscent + probe.fontBoundingBoxDescent};
}"""


@dataclass(frozen=True)
class Label:
    name: str
    text: str
    box: tuple[float, float, float, float]  # page px: left, top, right, bottom
    anchor: tuple[float, float]  # the thing it names, on the page (a robot, a ghost), if known
    owner: str = ""  # "robot 3", "ghost 1": what it must stay on


def _project(camera, canvas: dict, points: np.ndarray) -> np.ndarray:
    """Scene points (n, 3) to page pixels (n, 2) through a browser's camera as it reported it."""
    p, target = np.array(camera.position, dtype=float), np.array(camera.look_at, dtype=float)
    f = (target - p) / np.linalg.norm(target - p)
    r = np.cross(f, [0.0, 0.0, 1.0])
    r /= np.linalg.norm(r)
    u = np.cross(r, f)
    t = np.tan(float(camera.fov) / 2)
    d = points - p
    depth = d @ f
    ndc_x = (d @ r) / (depth * t * (canvas["width"] / canvas["height"]))
    ndc_y = (d @ u) / (depth * t)
    return np.stack(
        [canvas["x"] + (1 + ndc_x) * canvas["width"] / 2, canvas["y"] + (1 - ndc_y) * canvas["height"] / 2],
        axis=1,
    )


def _label_nodes(app: App, screen) -> list[tuple[str, object]]:
    """Every visible label of what this page shows: the shared scene's (both runs of Compare) and its
    own selection layer's."""
    renderers = [app.renderer, *([app.pair.second] if app.pair.second is not None else []), screen.selection]
    out = []
    for renderer in renderers:
        for name, handle in renderer.nodes().items():
            if type(handle).__name__ == "LabelHandle" and handle.visible and handle.text:
                out.append((renderer.prefix + name, handle))
    return out


def scene_labels(app: App, page, screen) -> tuple[list[Label], float, float]:
    """The page's labels as boxes in page pixels, what each is on, a cell's size in pixels, and the
    robot numbers' size in px."""
    camera = screen.client.camera
    canvas = page.locator("canvas").first.bounding_box()
    nodes = _label_nodes(app, screen)
    scales = {float(h.font_screen_scale) for _, h in nodes} or {1.0}
    em = SCREEN_EM_PX * min(scales)
    font = f"{SCREEN_EM_PX * max(scales)}px {LABEL_FONT_STACK}"
    measured = page.evaluate(MEASURE_JS, [[h.text for _, h in nodes], font])
    line = measured["line"]
    pad = PADDING * line
    anchors = _project(camera, canvas, np.array([h.position for _, h in nodes], dtype=float).reshape(-1, 3))
    origin = _project(camera, canvas, np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]))
    cell = float(np.linalg.norm(origin[1] - origin[0]))
    view = app.session.view()
    robots = {}
    for renderer, v in ((app.renderer, view), (app.pair.second, view.compare)):
        if renderer is None or v is None:
            continue
        pts = np.array([[*renderer.to_scene(r.position), 0.0] for r in v.robots], dtype=float).reshape(-1, 3)
        robots[renderer.prefix] = _project(camera, canvas, pts)
    ghosts = screen.selection
    ghost_at = {}
    if view.ghosts:  # a ghost that only changed light is a badge at its robot's upper left
        badge = np.array(GHOST_BADGE_OFFSET, dtype=float)
        pts = np.array(
            [
                [*(np.array(ghosts.to_scene(g.at)) + (badge if g.light_only else 0.0)), 0.0]
                for g in view.ghosts
            ],
            dtype=float,
        )
        ghost_at = {
            f"{g.robot}′": xy for g, xy in zip(view.ghosts, _project(camera, canvas, pts), strict=True)
        }
    out = []
    for (name, handle), width, (ax, ay) in zip(nodes, measured["widths"], anchors, strict=True):
        # viser's anchors: the padded block sits above the point, starting, ending or centred on it
        w = width + pad
        left = {"bottom-left": ax, "bottom-right": ax - w, "bottom-center": ax - w / 2}[handle.anchor]
        box = (left, ay - line - pad, left + w, ay)
        owner, at = "", (np.nan, np.nan)
        words = handle.text.split()
        if "/numbers/" in name and words[0].isdigit():
            prefix = "/compare" if name.startswith("/compare") else ""
            owner, at = f"robot {words[0]}", tuple(robots[prefix][int(words[0])])
        elif "/ghosts/numbers" in name and handle.text in ghost_at:
            owner, at = f"ghost {handle.text}", tuple(ghost_at[handle.text])
        out.append(Label(name, handle.text, box, at, owner))
    return out, cell, em


def _overlap(a, b) -> float:
    w = min(a[2], b[2]) - max(a[0], b[0])
    h = min(a[3], b[3]) - max(a[1], b[1])
    return max(0.0, w) * max(0.0, h)


def _distance(box, point) -> float:
    dx = max(box[0] - point[0], 0.0, point[0] - box[2])
    dy = max(box[1] - point[1], 0.0, point[1] - box[3])
    return float(np.hypot(dx, dy))


def settled_label_problems(app: App, page, screen, others, where: str, timeout: float = 10.0) -> list[str]:
    """The labels' problems on the projector and the pages beside it, read until there are none or
    ``timeout`` s have passed: labels are laid out anew for the zoom a page reports, and a loaded machine
    was once read while a page's report was on its way (the numbers over a region's name for a frame)."""
    end = time.time() + timeout
    while True:
        labels, cell, em = scene_labels(app, page, screen)
        found = [f"{where}: robot numbers at {em:.1f} px"] if em < NUMBER_PX else []
        found += [f"{where}: {p}" for p in label_problems(labels, cell)]
        for laptop, its_screen in others:
            labels, cell, _ = scene_labels(app, laptop, its_screen)
            found += [f"{where} at 1400×900: {p}" for p in label_problems(labels, cell)]
        if not found or time.time() > end:
            return found
        time.sleep(0.5)


def label_problems(labels: list[Label], cell: float) -> list[str]:
    """Two labels' boxes that overlap (by more than a pixel's sliver), a label farther than a cell from
    what it names."""
    out = []
    for i, a in enumerate(labels):
        for b in labels[i + 1 :]:
            if _overlap(a.box, b.box) > 2.0:
                out.append(f"“{a.text}” over “{b.text}”")
        if a.owner and _distance(a.box, a.anchor) > cell + 0.5:
            out.append(
                f"“{a.text}” {_distance(a.box, a.anchor):.0f} px from its {a.owner} (a cell: {cell:.0f} px)"
            )
    return out


def walk(browser, title: str, size: tuple[int, int], beside: tuple[int, int] | None = None):
    """Open ``title`` as `serve --lecture` does (presenting), then PageDown to its last stop; yields
    (index, stop, page, app, screen, others) at each stop, the run settled and each camera where it was
    sent. ``beside``: a second window of that size at the class address (a student's laptop, following
    the presenter's selection), also presenting; ``others`` holds its (page, screen)."""
    lecture = lectures()[title]
    session = demo_session()
    session.start_lecture(lecture)
    app = App(session, port=free_port(), verbose=False, present=True)
    pages: list = []
    opened: list = []
    try:
        windows = [(app.addresses[0], size), *([(app.addresses[1], beside)] if beside else [])]
        for address, (w, h) in windows:
            page = browser.new_page(viewport={"width": w, "height": h})
            page.set_default_timeout(60_000)
            pages.append(page)
            page.goto(address)
            page.locator("[data-apf=title]").wait_for()  # as `serve --lecture` opens: presenting, at stop 1
            connected = len(pages)
            wait_for(lambda connected=connected: len(app.screens) == connected)
            (screen,) = [x for x in app.screens.values() if x not in opened]
            opened.append(screen)
            wait_for(lambda screen=screen: screen.panels.presenting)
            software = page.locator(".mantine-Notification-root").filter(has_text="Software WebGL")
            if software.count():  # a headless browser's own warning, over the canvas: not the lecture's
                software.first.locator("button").click()
        page, screen = pages[0], opened[0]
        run = next(f for f in screen.panels.folders if hasattr(f, "lecture"))
        wait_for(lambda: run.lecture.value == title)  # the dropdown names it
        for i, stop in enumerate(lecture.stops):
            if i:
                page.keyboard.press("PageDown")
            wait_for(lambda i=i: app.session.lecturer.position == i, timeout=120)
            for p, x in zip(pages, opened, strict=True):
                settled(app, x)
                p.wait_for_function(
                    "t => document.querySelector('[data-apf=title]')?.innerText === t", arg=_plain(stop.title)
                )
            time.sleep(0.6)  # the last frame's labels reach the pages
            view = app.session.view()
            cells = [r.position for r in view.robots] + list(view.targets)
            for p, x in zip(pages, opened, strict=True):
                inside = inside_canvas(app, p, x.client.client_id, cells, CAPTION_ROOM)
                assert inside == [], f"{stop.title}: run under the caption"
                covered = p.evaluate(COVERED_JS)
                assert not covered, f"{stop.title}: a notification over the caption: {covered}"
            yield i, stop, page, app, screen, list(zip(pages[1:], opened[1:], strict=True))
    finally:
        for p in pages:
            p.close()
        app.stop()


def _plain(text: str) -> str:
    """A stop's title as the page shows it as text (a symbol's sub/superscript joined to its letter)."""
    import re

    return re.sub(r"_\{?([^}\s^]+)\}?", r"\1", text).replace("^", "")


@pytest.mark.parametrize("title", sorted(lectures()))
def test_every_stop_reads_from_the_back_row_with_labels_on_their_robots_at_1024x768_and_1400x900(
    browser, title
):
    """The projector (1024×768, presenting) and a student's laptop beside it (1400×900, the class
    address, presenting too): the caption's sizes on the projector, the labels on both (they are laid
    out once, for the page that shows them largest)."""
    problems = []
    for i, stop, page, app, screen, others in walk(browser, title, (1024, 768), beside=(1400, 900)):
        slug = title.split()[0].lower() + "-" + "-".join(title.split()[1:3]).lower()
        page.screenshot(path=str(OUT / f"projector-{slug}-1024-{i + 1:02d}.png"))
        caption = page.evaluate(CAPTION_JS)
        where = f"stop {i + 1} “{stop.title}”"
        if caption["title"] < TITLE_PX or caption["say"] < WORDS_PX:
            problems.append(f"{where}: title {caption['title']} px, words {caption['say']} px")
        small = [(px, text) for px, text in caption["sizes"] if px < WORDS_PX]
        if small:
            problems.append(f"{where}: text under {WORDS_PX} px: {small[:3]}")
        scroll, client = caption["scroll"]
        if caption["top"] != 0:
            problems.append(f"{where}: the caption opens scrolled ({caption['top']} px)")
        if scroll > client + 1:
            problems.append(f"{where}: the caption's words run {scroll - client} px past its box")
        if caption["panel"][1] > 0.35 * 768 + 0.5:
            problems.append(f"{where}: the caption is {caption['panel'][1]:.0f} px tall, over 35 % of 768")
        if stop.say.split()[0] not in caption["text"]:
            problems.append(f"{where}: its words are not on the page")
        if " I shows " in f" {stop.say} " or " I lists " in f" {stop.say} ":  # the words send the room to I
            problems += [f"{where}: {p}" for p in _details_shown(page, app, i, slug)]
        problems += settled_label_problems(app, page, screen, others, where)
        if not _framed_on_the_run(app, screen):  # a stop's run to its moment grew it: framed again
            problems.append(f"{where}: framed {screen.state.framed_bounds}, the run is {app.renderer.bounds}")
    assert not problems, "\n".join(problems)


def _framed_on_the_run(app: App, screen, timeout: float = 10.0) -> bool:
    """The projector's camera, which nobody moved, frames the run's own box at a stop (not one grown with
    room to spare while the stop's run played to its moment: robots drawn at 60 % of their size)."""
    try:
        wait_for(lambda: screen.state.framed_bounds == app.renderer.bounds, timeout)
    except AssertionError:
        return False
    return True


def _details_shown(page, app: App, i: int, slug: str) -> list[str]:
    """I at a stop whose words promise the details: they show, at 20 px, what the words promised (whose
    stale decision, who waits on what); I again gives the words back."""
    view = app.session.view()
    promised = (view.fatal[0] or view.waits).split("\n")[0][:40]
    page.keyboard.press("i")
    page.wait_for_function("() => /details · I: back to the words/.test(document.body.innerText)")
    page.screenshot(path=str(OUT / f"projector-{slug}-1024-{i + 1:02d}-details.png"))
    out = []
    text = page.evaluate("() => document.querySelector('[data-apf=details]').innerText")
    if not promised or promised not in text:
        out.append(f"I shows no “{promised}”")
    sizes = page.evaluate(
        "() => [...document.querySelectorAll('[data-apf=details] *')].filter(e => !e.closest('sub,sup') && "
        "[...e.childNodes].some(n => n.nodeType === 3 && n.textContent.trim()))"
        ".map(e => parseFloat(getComputedStyle(e).fontSize))"
    )
    if min(sizes) < WORDS_PX:
        out.append(f"the details at {min(sizes)} px")
    page.keyboard.press("i")
    page.locator("[data-apf=title]").wait_for()
    return out


def test_caption_room_is_the_share_the_test_holds():
    assert CAPTION_ROOM <= 0.35


def test_play_then_pagedown_lands_where_pagedown_alone_lands(browser):
    """At stop 3 of the 12-stop lecture, Space plays the run on: the caption says so at once (its words
    were about stop 3's moment); PageDown, still playing, then shows stop 4 at the very event, robots and
    caption that PageDown alone shows."""
    title = "The algorithm in 12 stops"
    alone = demo_session()
    alone.start_lecture(lectures()[title])
    for _ in range(3):
        alone.next_stop()
    expected = (alone.engine.state.events, alone.engine.current_points(), alone.view().lecture)
    stops = walk(browser, title, (1024, 768))
    try:
        for _ in range(3):  # to stop 3
            _, _, page, app, _, _ = next(stops)
        s = app.session
        at = s.engine.state.events
        page.keyboard.press("Space")
        page.wait_for_function("() => /Playing on from stop 3/.test(document.body.innerText)")
        wait_for(lambda: s.engine.state.events > at + 50)  # played well past stop 3
        page.screenshot(path=str(OUT / "projector-played-on-from-stop-3.png"))
        page.keyboard.press("PageDown")
        wait_for(lambda: s.lecturer.position == 3 and not s.playing)
        page.wait_for_function(
            "t => document.querySelector('[data-apf=title]')?.innerText === t", arg=_plain(expected[2][1])
        )
        assert (s.engine.state.events, s.engine.current_points(), s.view().lecture) == expected
        text = page.evaluate(CAPTION_JS)["text"]
        assert "Played on" not in text and "Playing on" not in text and f"event {expected[0]}" in text
        page.screenshot(path=str(OUT / "projector-stop-4-after-play.png"))
    finally:
        stops.close()


STARTS_JS = "() => JSON.parse(document.getElementById('apf-stops').textContent).stops.map(s => s.at)"


def test_the_exported_lecture_opens_paused_and_goes_stop_to_stop_from_disk_with_no_network(browser, tmp_path):
    """`apf-viz export --lecture` opened from file:// with every request off the disk refused: paused at
    stop 1, PageDown / PageUp and the arrows go stop to stop (the run and an HTML caption at the
    projector's sizes), and Space still plays, the caption following the stops."""
    from apf_viz.cli import main

    out = tmp_path / "lecture.html"
    assert main(["export", "--lecture", "where-the-paper-breaks", "--out", str(out)]) == 0
    stops = lectures()["Where the paper breaks under ASYNC"].stops
    context, refused = offline_context(browser)
    page = context.new_page()
    try:
        page.goto(out.as_uri())
        title = page.locator("#apf-caption [data-apf=title]")
        title.wait_for()
        time_field = page.locator("input.mantine-NumberInput-input")
        page.wait_for_function("() => document.title.endsWith('stop 1')")
        time.sleep(2.0)  # paused: two seconds later it is still at stop 1's moment
        assert float(time_field.input_value()) == pytest.approx(0.1) and title.inner_text() == stops[0].title
        first = _canvas(page)
        assert first.std() > 5  # it draws
        sizes = page.evaluate(
            "() => ['title', 'say'].map(k => parseFloat(getComputedStyle("
            "document.querySelector('#apf-caption [data-apf=' + k + ']')).fontSize))"
        )
        assert sizes[0] >= TITLE_PX and sizes[1] >= WORDS_PX
        box = page.locator("#apf-caption").bounding_box()
        assert box["height"] <= 0.35 * 768
        starts = page.evaluate(STARTS_JS)  # each stop's second (a question's reveal adds one of its own)
        assert starts[:3] == [0.0, 12.0, 18.0]  # stop 1 asks: its reveal's frame follows it
        for key, index in (
            ("PageDown", 1),
            ("PageDown", 2),
            ("ArrowRight", 3),
            ("PageUp", 2),
            ("ArrowLeft", 1),
        ):
            page.keyboard.press(key)
            page.wait_for_function(
                "t => document.querySelector('#apf-caption [data-apf=title]').innerText === t",
                arg=_plain(stops[index].title),
            )
            assert float(time_field.input_value()) == pytest.approx(starts[index] + 0.1)
        page.screenshot(path=str(OUT / "projector-exported-page-stop-2.png"))
        changed = np.abs(_canvas(page) - first).max(axis=2) > 40
        changed[:320, :340] = False  # a headless browser's notification in the corner
        assert changed.sum() > 500  # stop 2's run, not stop 1's
        page.keyboard.press("Space")  # plays on: the caption follows the recording into stop 3
        page.wait_for_function(
            "t => document.querySelector('#apf-caption [data-apf=title]').innerText === t",
            arg=_plain(stops[2].title),
            timeout=20_000,
        )
        assert not refused, refused[:3]
    finally:
        context.close()


def test_the_exported_lecture_asks_its_question_and_reveals_the_answer_from_disk(browser, tmp_path):
    """The page taken home asks too: at stop 1 of `where-the-paper-breaks` the reader answers (changed
    once), reveals with R, and the page says the run's answer and goes to where the run shows it, with no
    server and no network."""
    from apf_viz.cli import main

    out = tmp_path / "lecture.html"
    assert main(["export", "--lecture", "where-the-paper-breaks", "--out", str(out)]) == 0
    context, refused = offline_context(browser)
    page = context.new_page()
    try:
        page.goto(out.as_uri())
        page.wait_for_function("() => document.title.endsWith('stop 1')")
        caption = page.locator("#apf-caption")
        caption.locator("[data-apf=question]").filter(has_text="how does the run end?").wait_for()
        time_field = page.locator("input.mantine-NumberInput-input")
        page.wait_for_function("() => document.querySelector('input.mantine-NumberInput-input')")
        first = _canvas(page)
        caption.locator("[data-choice=stuck]").click()
        caption.locator("[data-choice=collision]").click()  # changed before the reveal
        verdict = caption.locator("[data-apf=verdict]")
        assert "Your answer: collision" in verdict.inner_text()
        status = caption.locator(".status")
        before = status.inner_text()
        assert "event 41" not in before
        page.keyboard.press("r")
        page.wait_for_function(
            "() => document.querySelector('[data-apf=verdict]').innerText.includes(\"The run's answer\")"
        )
        assert (
            verdict.inner_text() == "The run's answer: collision (event 41). You answered collision: right."
        )
        assert status.inner_text().endswith("event 41")  # the state line follows the run to the answer
        reveal_at = page.evaluate(
            "() => JSON.parse(document.getElementById('apf-stops').textContent).stops[0].question.reveal_at"
        )
        assert float(time_field.input_value()) == pytest.approx(reveal_at + 0.1)
        time.sleep(1.0)
        changed = np.abs(_canvas(page) - first).max(axis=2) > 40
        changed[:320, :340] = False  # a headless browser's notification in the corner
        assert changed.sum() > 500  # the run as it collides, not as it starts
        page.screenshot(path=str(OUT / "projector-exported-question-revealed.png"))
        caption.locator("[data-choice=formed]").click()  # after the reveal, the answer stands
        assert "You answered collision: right." in verdict.inner_text()
        assert not refused, refused[:3]
    finally:
        context.close()


def test_the_caption_keeps_its_size_when_the_page_draws_at_a_lower_resolution():
    """Under load viser's client lowers its pixel ratio to ⅞ or ¾ and reports a smaller canvas of the
    same shape: the caption keeps the size it was laid out for (it ran 22–33 px past its box at 1024×768
    when it followed). A canvas of another shape is a resized window: the caption follows it."""
    from apf_viz.ui.panels.presentation import steady_size

    seen = steady_size(None, (768, 1024))
    for lowered in ((672, 896), (576, 768), (672, 896)):
        seen = steady_size(seen, lowered)
        assert seen == (768, 1024)
    assert steady_size(seen, (768, 1024)) == (768, 1024)
    assert steady_size((576, 768), (768, 1024)) == (768, 1024)  # first reported lowered, then in full
    resized = steady_size(seen, (700, 1400))
    assert resized == (700, 1400) and steady_size(resized, (612, 1225)) == (700, 1400)
    assert steady_size(resized, (700, 1000)) == (700, 1000)  # narrower: the caption follows
