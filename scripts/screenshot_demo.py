"""Regenerate the README's screenshot, static/demo-midrun.png: the built-in demo mid-run, with a robot
selected that holds a stale snapshot (rays and ghosts shown).

Run: python scripts/screenshot_demo.py [--out static/demo-midrun.png]
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from playwright.sync_api import sync_playwright

from apf_viz.ui.app import App, demo_session, free_port


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default="static/demo-midrun.png")
    args = ap.parse_args()
    session = demo_session()
    engine = session.engine
    while sum(light == "done" for light in engine.state.lights) < 4 and session.step():
        pass
    while True:  # stop where some robot holds a snapshot older than the configuration
        st = engine.state
        stale = [r for r in range(engine.k) if st.phase[r] != 0 and st.look_version[r] != st.version]
        if stale or not session.step():
            break
    session.selected = stale[0] if stale else 0
    app = App(session, port=free_port(), verbose=False)
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=["--no-sandbox"])
        page = browser.new_page(viewport={"width": 1400, "height": 900})
        page.goto(f"http://127.0.0.1:{app.port}")
        page.get_by_label("Event").wait_for(timeout=60_000)
        time.sleep(3)
        for close in page.locator(".mantine-Notification-closeButton").all():
            close.click()
        time.sleep(1)
        Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        page.screenshot(path=args.out)
        browser.close()
    app.stop()
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
