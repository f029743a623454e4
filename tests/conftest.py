from __future__ import annotations

import json
from pathlib import Path

import pytest


@pytest.fixture
def write_json(tmp_path: Path):
    """Write an object (or raw text) to a file under tmp_path and return its path."""

    def _write(name: str, data) -> Path:
        p = tmp_path / name
        p.write_text(data if isinstance(data, str) else json.dumps(data))
        return p

    return _write


def unmarked_browser_tests(items: list) -> list[str]:
    """The tests that start Chromium (they ask for the ``browser`` fixture) without the ``browser`` mark:
    ``--quick`` leaves out exactly the marked ones, so an unmarked one would run there (and twice in CI,
    once more on the lowest versions)."""
    return [
        item.nodeid
        for item in items
        if "browser" in getattr(item, "fixturenames", ()) and item.get_closest_marker("browser") is None
    ]


def pytest_collection_modifyitems(config, items) -> None:
    unmarked = unmarked_browser_tests(items)
    if unmarked:
        raise pytest.UsageError(
            f"{len(unmarked)} tests start Chromium without @pytest.mark.browser: {', '.join(unmarked[:5])}"
        )


@pytest.fixture(scope="module")
def browser():
    """Debian's Chromium driven by Playwright, one for a test module (tests/test_ui_browser.py says how it
    is launched); playwright is imported only by the tests that ask for it."""
    sync = pytest.importorskip("playwright.sync_api")
    from tests.test_ui_browser import ARGS, CHROMIUM

    with sync.sync_playwright() as p:
        b = p.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        yield b
        b.close()


@pytest.fixture
def demo_app():
    """A visualiser on the Demo heart, on a free port, stopped after the test (a browser test's server)."""
    from apf_viz.ui.app import App, demo_session, free_port

    # Several class pages from this one machine, each a laptop of its own (a hall behind one router).
    a = App(demo_session(), port=free_port(), verbose=False, seats_per_address=8)
    yield a
    a.stop()
