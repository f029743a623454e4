"""Regenerate the README's screenshot, static/demo-midrun.png: the built-in demo mid-lecture, with a
robot selected that holds a stale snapshot (rays to where it saw the others, ghosts in the lights it
saw, the differences listed), the last event and the legend.

Run: python scripts/screenshot_demo.py [--out static/demo-midrun.png] [--width 1400 --height 900]
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from playwright.sync_api import sync_playwright

from apf_viz.ui.app import App, demo_session, free_port
from apf_viz.workbench.view_model.staleness import seen_robots


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default="static/demo-midrun.png")
    ap.add_argument("--width", type=int, default=1400)
    ap.add_argument("--height", type=int, default=900)
    args = ap.parse_args()
    session = demo_session()
    engine = session.engine
    while sum(light == "done" for light in engine.state.lights) < 4 and session.step():
        pass
    while True:  # stop where some robot holds a snapshot that another robot's move made stale
        moved = [any(s.seen_at != s.now_at for s in seen_robots(engine, r, "held")) for r in range(engine.k)]
        stale = [r for r in range(engine.k) if moved[r]]
        if stale or not session.step():
            break
    session.selected = stale[0] if stale else 0
    app = App(session, port=free_port(), verbose=False)
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=["--no-sandbox"])
        page = browser.new_page(viewport={"width": args.width, "height": args.height})
        page.goto(app.addresses[0])  # the presenter address: the panel a lecturer sees
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
