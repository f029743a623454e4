"""Visualiser benchmarks, measured in a real headless Chromium:

- scene update rate while playing with 1,000 robots (target ≥ 20 updates/s): how often the browser's
  `Event` number changes per second (each change is one rendered frame reaching the page), beside how
  many frames the page drew (a frame drawn before the next update arrives shows nothing new);
- click-to-update latency: Manual scheduler, a click on a robot, until the page shows the new event;
- with ``--to-formed``: a run played at the Speed slider's top from its start to FORMED, with a browser
  watching (wall time, and the page's update rate meanwhile);
- with ``--stage pattern``: the same measures in pattern formation, not leader election: the run is first
  stepped (no browser yet) until the leader is elected and ``--line`` robots have travelled to the line,
  so the scene holds the leader's frame, the line and all k targets.

Run: python benchmarks/bench_ui.py [--robots 1000] [--stage pattern];
python benchmarks/bench_ui.py --robots 100 --to-formed
"""

from __future__ import annotations

import argparse
import random
import statistics
import sys
import threading
import time

from playwright.sync_api import sync_playwright

import apf_viz.ui.run_controller as run_controller
from apf_viz.algorithms.apf_opaque_grid.audit import random_pattern, random_solvable_start
from apf_viz.ui.app import App, free_port
from apf_viz.ui.session import Session

ARGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
]

COUNT_CHANGES = """
async ([ms]) => {
  const input = [...document.querySelectorAll('label')].find(l => l.textContent === 'Event');
  const el = document.getElementById(input.htmlFor);
  let last = el.value, changes = 0, frames = 0;
  const t0 = performance.now();
  while (performance.now() - t0 < ms) {
    await new Promise(r => requestAnimationFrame(r));
    frames++;
    if (el.value !== last) { changes++; last = el.value; }
  }
  return [changes / (ms / 1000), frames / (ms / 1000)];
}
"""

WAIT_CHANGE = """
async () => {
  const input = [...document.querySelectorAll('label')].find(l => l.textContent === 'Event');
  const el = document.getElementById(input.htmlFor);
  const before = el.value, t0 = performance.now();
  window.__clickAt = t0;
  while (el.value === before && performance.now() - t0 < 5000) await new Promise(r => setTimeout(r, 1));
  return performance.now() - t0;
}
"""


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--robots", type=int, default=1000)
    ap.add_argument("--to-formed", action="store_true", help="play at top speed until the run ends")
    ap.add_argument("--stage", choices=("election", "pattern"), default="election")
    ap.add_argument("--line", type=int, default=20, help="with --stage pattern: robots on the line first")
    args = ap.parse_args()
    rng = random.Random(3)
    start = random_solvable_start(args.robots, rng)
    pattern = random_pattern(args.robots, rng)
    session = Session(start, pattern, seed=1)
    if args.stage == "pattern":
        reach_pattern_formation(session, args.line)
    app = App(session, port=free_port(), verbose=False)
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=ARGS)
        page = browser.new_page(viewport={"width": 1400, "height": 900})
        page.goto(f"http://127.0.0.1:{app.port}")
        page.get_by_label("Event").wait_for(timeout=60_000)
        time.sleep(2)
        if args.to_formed:
            to_formed(app, session, page)
            browser.close()
            app.stop()
            return
        session.set_speed(2000.0)  # the speed of every earlier measurement (the slider's top is 5,000)
        session.toggle_play()
        time.sleep(1)
        frames_before = app.frames
        stage_before = session.view().stage
        rate, page_fps = page.evaluate(COUNT_CHANGES, [5000])
        sent = (app.frames - frames_before) / 5.0
        session.pause()
        server_fps = app.frames
        where = f"{args.robots} robots, {args.stage}"
        # The engine is fast enough to leave a stage within the window: say where the window was.
        print(f"(the window ran from '{stage_before}' to '{session.view().stage}')")
        print(f"| scene updates/s in the browser while playing, {where} | {rate:.1f} |")
        print(f"| frames/s the server sent meanwhile (one atomic update each) | {sent:.1f} |")
        print(f"| frames/s the page drew meanwhile (some show no new update) | {page_fps:.1f} |")
        session.set_scheduler("manual")
        time.sleep(0.5)
        latencies = []
        for i in range(10):
            r = i * 7 % args.robots
            session.selected = r
            t0 = time.perf_counter()
            handle = page.evaluate_handle(WAIT_CHANGE)
            session.click(session.engine.current_points()[r])
            app.request_render()
            latencies.append(handle.json_value())
            _ = t0
        print(f"| click-to-update latency (median of 10), {where} | {statistics.median(latencies):.0f} ms |")
        print(f"(server rendered {server_fps} frames in all)")
        browser.close()
    app.stop()


def reach_pattern_formation(session: Session, line: int) -> None:
    """Step the run without a browser until a leader exists and ``line`` robots have been sent to the line
    (progress on stderr)."""
    engine = session.engine
    t0 = time.perf_counter()
    while engine.outcome is None and "leader" not in engine.state.lights:
        session.run.step()
    moved_in = 0
    while engine.outcome is None and moved_in < line:
        session.run.step()
        events = engine.history.steps[engine.step_index - 1].events
        moved_in += sum(1 for e in events if (e.rule_id or "").endswith("LineMove.into-line"))
    print(
        f"(stepped to pattern formation in {time.perf_counter() - t0:.0f} s: {engine.state.moves:,} moves, "
        f"{moved_in} robots sent into the line)",
        file=sys.stderr,
    )


def to_formed(app: App, session: Session, page) -> None:
    """Play at the slider's top until the run ends: the end is seen by polling the engine every 10 ms
    (a thread), while the page's update rate is sampled in 2-second windows."""
    session.set_speed(run_controller.MAX_SPEED)
    ended: list[float] = []

    def watch() -> None:
        while session.engine.outcome is None and time.perf_counter() - t0 < 1800:
            time.sleep(0.01)
        ended.append(time.perf_counter())

    t0 = time.perf_counter()
    session.toggle_play()
    watcher = threading.Thread(target=watch, daemon=True)
    watcher.start()
    rates = []
    while watcher.is_alive():
        rate, _ = page.evaluate(COUNT_CHANGES, [2000])
        if watcher.is_alive():  # a window that saw the run end would count the idle page too
            rates.append(rate)
    wall = ended[0] - t0
    st = session.engine.state
    shown = f"median {statistics.median(rates):.1f}, min {min(rates):.1f}" if rates else "(under 2 s)"
    print(
        f"| {session.engine.k} robots played to {session.engine.outcome} at {run_controller.MAX_SPEED:.0f} "
        f"steps/s requested | {wall:.1f} s | {st.events:,} events, {st.moves:,} moves | page updates/s: "
        f"{shown} |"
    )


if __name__ == "__main__":
    main()
