"""viser's insides behind one door (apf_viz/ui/viser_compat.py): a contract test for each access (fails
when a viser release changes it), each one's absence named with its cost in one terminal line, and the
presenter taking control by the public fallback when the websocket path is hidden."""

from __future__ import annotations

import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
import viser

from apf_viz.ui import viser_compat
from apf_viz.ui.network import free_port

ROOT = Path(__file__).resolve().parent.parent


def test_this_viser_offers_every_inside_apf_viz_uses():
    """The installed viser (the range pyproject.toml declares) lacks none: the server says nothing."""
    assert viser_compat.missing() == []
    assert viser_compat.startup_line([]) is None


def test_the_websocket_path_of_a_live_connection_is_read():
    """What roles and seats stand on: the path a page opened its websocket at, and the address it came
    from, read off viser's live connection."""
    from websockets.sync.client import connect

    port = free_port()
    server = viser.ViserServer(port=port, verbose=False)
    try:
        with connect(f"ws://127.0.0.1:{port}/present/abc", subprotocols=[f"viser-v{viser.__version__}"]):
            end = time.time() + 10
            while viser_compat.websocket_path(server, 0) is None and time.time() < end:
                time.sleep(0.05)
            assert viser_compat.websocket_path(server, 0) == "/present/abc"
            assert viser_compat.remote_address(server, 0) == "127.0.0.1"  # what seats are issued to
        assert viser_compat.websocket_path(server, 99) is None  # no such page: no path, no error
        assert viser_compat.remote_address(server, 99) is None
    finally:
        server.stop()


def test_a_sliders_marks_are_set_and_a_notifications_state_is_read():
    """The timeline's stage marks (no public setter) and a notification's removed flag."""
    from viser._messages import GuiSliderMark

    server = viser.ViserServer(port=free_port(), verbose=False)
    try:
        slider = server.gui.add_slider("Timeline", min=0, max=10, step=1, initial_value=0)
        viser_compat.set_slider_marks(slider, [(1, "Phase 1"), (4, None)])
        assert slider._marks == (GuiSliderMark(1.0, "Phase 1"), GuiSliderMark(4.0, None))
        viser_compat.set_slider_marks(slider, [])
        assert slider._marks is None
    finally:
        server.stop()

    class Closed:  # the shape viser's NotificationHandle has (its state, removed once closed)
        class _impl:
            removed = True

    assert viser_compat.notification_removed(Closed()) and not viser_compat.notification_removed(object())


@pytest.mark.parametrize("name", [a.name for a in viser_compat.ACCESSES])
def test_a_missing_inside_is_named_with_its_cost(monkeypatch, name):
    access = next(a for a in viser_compat.ACCESSES if a.name == name)
    hidden = tuple(
        viser_compat.Access(a.name, (lambda: 1 / 0) if a is access else a.present, a.cost)
        for a in viser_compat.ACCESSES
    )  # an inside that changed shape raises: missing, whatever it raised
    monkeypatch.setattr(viser_compat, "ACCESSES", hidden)
    absent = viser_compat.missing()
    assert [a.name for a in absent] == [name]
    line = viser_compat.startup_line(absent)
    assert line is not None and "\n" not in line and name in line and access.cost in line


HIDE = """
import sys
import viser.infra._infra as infra
from apf_viz.ui import viser_compat
del infra._message_producer  # a viser whose producer moved
viser_compat.websocket_path = lambda server, client_id: None  # and whose connections say no path
viser_compat.ACCESSES = tuple(
    viser_compat.Access(a.name, (lambda: False) if a.name == "websocket path" else a.present, a.cost)
    for a in viser_compat.ACCESSES
)
from apf_viz.cli import main
sys.exit(main(sys.argv[1:]))
"""


def test_serve_says_in_one_line_what_it_cannot_use_and_prints_the_presenter_code():
    """viser's producer and websocket paths hidden: serve still serves, and says once what it lacks and
    what that costs, then the code a presenter types."""
    port = free_port()
    proc = subprocess.Popen(
        [sys.executable, "-c", HIDE, "serve", "--port", str(port)],
        cwd=ROOT,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        # A background job of a non-interactive shell ignores SIGINT, and a Python started so keeps it
        # ignored: the Ctrl+C below must reach it however the suite was started (tests/sweep_helpers.py).
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    try:
        lines = []
        assert proc.stdout is not None
        while not any(line.startswith("presenter code:") for line in lines):
            line = proc.stdout.readline()
            assert line, proc.stderr.read() if proc.stderr else ""
            lines.append(line.strip())
        lacks = [line for line in lines if "lacks" in line]
        assert len(lacks) == 1
        assert "shared producer (class pages are serialised once each: slower with many pages)" in lacks[0]
        assert "websocket path (every page opens as a class page" in lacks[0]
    finally:
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=60)
    assert proc.returncode == 0 and "Traceback" not in err


@pytest.mark.browser
def test_with_the_websocket_path_hidden_a_presenter_takes_control_by_the_code(monkeypatch, browser):
    """Every page opens as a class page (nothing of the presenter's controls); the presenter address's
    page types a wrong code (told so), then the code the terminal printed: Step appears and Enter steps
    the shared run."""
    from apf_viz.ui.app import App, demo_session
    from tests.test_ui_browser import wait_for

    monkeypatch.setattr(viser_compat, "websocket_path", lambda server, client_id: None)
    hidden = tuple(
        viser_compat.Access(a.name, (lambda: False) if a.name == "websocket path" else a.present, a.cost)
        for a in viser_compat.ACCESSES
    )
    monkeypatch.setattr(viser_compat, "ACCESSES", hidden)
    app = App(demo_session(), port=free_port(), verbose=False)
    try:
        assert app.by_code
        page = browser.new_page(viewport={"width": 1400, "height": 900})
        page.set_default_timeout(60_000)
        page.goto(app.addresses[0])  # the presenter address: its secret cannot be read here
        page.get_by_label("Event").wait_for()
        wait_for(lambda: len(app.screens) == 1)
        (screen,) = app.screens.values()
        assert screen.state.role == "class" and not page.get_by_role("button", name="Step").is_visible()
        # viser's text field has no id for its label: the input in the label's row
        field = (
            page.locator("label", has_text="Presenter code")
            .locator("xpath=ancestor::div[2]")
            .locator("input")
        )
        field.fill("0000000000")
        field.press("Enter")
        page.get_by_text("that is not the presenter code").first.wait_for()
        field.press_sequentially(app.roles.code)  # key by key: the partial code is not a try
        page.get_by_text("this page presents").first.wait_for()
        page.get_by_role("button", name="Step").wait_for(state="visible")
        assert screen.state.role == "presenter" and not field.is_visible()
        page.keyboard.press("Escape")
        page.keyboard.press("Enter")
        wait_for(lambda: app.session.engine.step_index == 1)
        page.close()
    finally:
        app.stop()
