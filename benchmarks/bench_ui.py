"""Visualiser benchmarks, measured in a real headless Chromium:

- scene update rate while playing with 1,000 robots (target ≥ 20 updates/s): how often the browser's
  `Event` number changes per second (each change is one rendered frame reaching the page), beside how
  many frames the page drew (a frame drawn before the next update arrives shows nothing new);
- with ``--stage election`` (the default): the window is leader election itself, from the first step of
  the run until the leader stands at its corner (at 1,000 robots 38 events, about half a second of play
  at 2,000 steps/s: its steps are the dearest of the run, every robot seeing hundreds; the longest wait
  for an update says more than a rate over so short a window). The event that ends it is
  found first by stepping a copy of the run without a browser. The update rate counted after it, to the
  end of a 5-second window, is printed too, as the start of pattern formation;
- with ``--stage targets``: the last stage, the line complete and its robots leaving it one by one for
  their targets (stepped to without a browser first: about four minutes at 1,000 robots), then the same
  three windows;
- with ``--stage pattern``: pattern formation: the run is first stepped (no browser yet) until the
  leader is elected and ``--line`` robots have travelled to the line, so the scene holds the leader's
  frame, the line and all k targets; then three 5-second windows of play after a first second. Each
  prints the canvas's pixel ratio: viser's page lowers it (to 0.75 of the screen's) when it draws
  fewer than 38 frames/s for 2.5 s, twice, so a software-rendered page settles at 0.75 after about 5 s
  of play; the last window is that steady state, the first the page still at full resolution;
- click-to-update latency: Manual scheduler, a click on a robot, until the page shows the new event;
- with ``--to-formed``: a run played at the Speed slider's top from its start to FORMED, with a browser
  watching (wall time, and the page's update rate meanwhile);
- with ``--class N``: a lecture hall (bench_class.py): the heart demo played at 30 steps/s, a real
  projector page at 1024×768 and a real student page, first alone, then with N lightweight class pages
  (websocket clients that send a camera as a page does, read every message, and have each selected a
  robot); each page's scene updates/s in both, and the projector's share of its rate alone;
- with ``--own N``: the same, each of the N class pages trying a run of its own and playing it at the
  fastest an own run may; and the server's memory before, with and after the class;
- with ``--room A,O``: the same with A class pages that each answered a lecture stop's question and O
  each playing a run of its own; then how long the presenting projector takes to count one answer more;
- with ``--churn N``: N pages that connect and read nothing (laptops asleep) while the run plays, then
  vanish without a goodbye (their process killed), three times: the server's memory after each round;
- with ``--short N``: N class pages that each stay a moment (a camera sent, 0.3 s read, a clean goodbye),
  20 at a time, each with a seat of its own: the server's memory before and after, and the pages held;
- with ``--wake N [--asleep S]``: N pages that read nothing for S seconds (default 60) while the run
  plays, then wake: how long until each shows the run's event, the server's frames/s meanwhile.

Run: python benchmarks/bench_ui.py [--robots 1000] [--stage pattern|targets] [--window 1024x768];
python benchmarks/bench_ui.py --robots 100 --to-formed; python benchmarks/bench_ui.py --class 60;
python benchmarks/bench_ui.py --churn 200; python benchmarks/bench_ui.py --short 2000;
python benchmarks/bench_ui.py --wake 20;
python benchmarks/bench_ui.py --own 24; python benchmarks/bench_ui.py --room 60,20
"""

from __future__ import annotations

import argparse
import itertools
import random
import statistics
import sys
import threading
import time

from playwright.sync_api import sync_playwright

import apf_viz.workbench.run_controller as run_controller
from apf_viz.algorithms.apf_opaque_grid.audit import random_pattern, random_solvable_start
from apf_viz.ui.app import App, free_port
from apf_viz.workbench.session import Session

ARGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
]

# Started without waiting for it (the promise is kept in the page), so that the click or the play that
# it measures happens while it already watches; collected later by awaiting window.__probe.
START_WAIT_CHANGE = """
() => {
  const input = [...document.querySelectorAll('label')].find(l => l.textContent === 'Event');
  const el = document.getElementById(input.htmlFor);
  const before = el.value, t0 = performance.now();
  window.__probe = (async () => {
    while (el.value === before && performance.now() - t0 < 5000) await new Promise(r => setTimeout(r, 1));
    return performance.now() - t0;
  })();
}
"""

# The WebGL canvas's drawing-buffer pixels per CSS pixel (viser's adaptive resolution); the other canvas
# on the page, a selection overlay, is 0×0 while unused.
PIXEL_RATIO = """
() => {
  const c = [...document.querySelectorAll('canvas')].sort((a, b) => b.width - a.width)[0];
  return c.width / c.clientWidth;
}
"""

# Every animation frame's time and every change of the Event number (time, new value), for ms.
START_RECORD = """
([ms]) => {
  const input = [...document.querySelectorAll('label')].find(l => l.textContent === 'Event');
  const el = document.getElementById(input.htmlFor);
  window.__probe = (async () => {
    let last = el.value;
    const frames = [], changes = [], t0 = performance.now();
    while (performance.now() - t0 < ms) {
      await new Promise(r => requestAnimationFrame(r));
      const t = performance.now() - t0;
      frames.push(t);
      if (el.value !== last) { last = el.value; changes.push([t, Number(last)]); }
    }
    return [frames, changes];
  })();
}
"""


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--robots", type=int, default=1000)
    ap.add_argument("--to-formed", action="store_true", help="play at top speed until the run ends")
    ap.add_argument("--stage", choices=("election", "pattern", "targets"), default="election")
    ap.add_argument("--line", type=int, default=20, help="with --stage pattern: robots on the line first")
    ap.add_argument("--speed", type=float, default=2000.0, help="steps/s requested while playing")
    ap.add_argument("--window", default="1400x900", help="WIDTHxHEIGHT (a projector: 1024x768)")
    ap.add_argument("--class", dest="pages", type=int, default=None, help="N lightweight class pages")
    ap.add_argument("--own", type=int, default=None, help="N class pages each playing a run of its own")
    ap.add_argument(
        "--room",
        default=None,
        help="A,O: A class pages that answered a stop's question, O trying runs of their own",
    )
    ap.add_argument("--churn", type=int, default=None, help="N pages connected, asleep, then killed")
    ap.add_argument("--short", type=int, default=None, help="N class pages that each stay a moment")
    ap.add_argument("--wake", type=int, default=None, help="N pages asleep while the run plays, then awake")
    ap.add_argument("--asleep", type=float, default=60.0, help="with --wake: seconds asleep")
    args = ap.parse_args()
    if args.room is not None:
        from bench_class import lecture_hall

        answering, own = (int(x) for x in args.room.split(","))
        lecture_hall(answering + own, ARGS, START_RECORD, answering=answering)
        return
    if args.pages is not None or args.own is not None:
        from bench_class import lecture_hall

        lecture_hall(args.pages or args.own, ARGS, START_RECORD, own=args.own is not None)
        return
    if args.churn is not None:
        from bench_class import churn

        churn(args.churn)
        return
    if args.short is not None:
        from bench_class import short_stays

        short_stays(args.short)
        return
    if args.wake is not None:
        from bench_class import sleep_and_wake

        sleep_and_wake(args.wake, args.asleep)
        return
    rng = random.Random(3)
    start = random_solvable_start(args.robots, rng)
    pattern = random_pattern(args.robots, rng)
    session = Session(start, pattern, seed=1)
    elected_at = None
    if args.stage == "pattern":
        reach_pattern_formation(session, args.line)
    elif args.stage == "targets":
        reach_targets(session)
    elif not args.to_formed:
        elected_at = election_end(Session(start, pattern, seed=1))
    app = App(session, port=free_port(), verbose=False)
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=ARGS)
        width, height = (int(v) for v in args.window.split("x"))
        page = browser.new_page(viewport={"width": width, "height": height})
        page.goto(f"http://127.0.0.1:{app.port}")
        page.get_by_label("Event").wait_for(timeout=60_000)
        time.sleep(2)
        if args.to_formed:
            to_formed(app, session, page)
            browser.close()
            app.stop()
            return
        session.set_speed(args.speed)  # 2,000: the speed of every earlier measurement (the top is 5,000)
        where = f"{args.robots} robots, {args.stage}, {args.speed:g} steps/s, {args.window}"
        stage_before = session.view().stage
        if elected_at is not None:  # leader election: the window starts with the run
            ratio = page.evaluate(PIXEL_RATIO)
            frames_before = app.frames
            page.evaluate(START_RECORD, [5000])
            session.toggle_play()
            frames, changes = page.evaluate("window.__probe")
            sent = (app.frames - frames_before) / 5.0
            election_window(frames, changes, elected_at, where)
            print(f"| frames/s the server sent in the 5-second window (one update each) | {sent:.1f} |")
            end_ratio = page.evaluate(PIXEL_RATIO)
            print(f"(the canvas's pixel ratio: {ratio:.2f} at the start, {end_ratio:.2f} at the end)")
        else:  # a later stage: a second of play first, then the windows
            session.toggle_play()
            time.sleep(1)
            print(f"(from '{stage_before}')")
            for window in range(3):
                pattern_window(app, page, f"{where}, {1 + 5 * window}–{6 + 5 * window} s of play")
            print(f"(to '{session.view().stage}')")
        session.pause()
        server_fps = app.frames
        session.set_scheduler("manual")
        time.sleep(0.5)
        latencies = []
        for i in range(10):
            r = i * 7 % args.robots
            session.selected = r
            page.evaluate(START_WAIT_CHANGE)
            session.click(session.engine.current_points()[r])
            app.request_render()
            latencies.append(page.evaluate("window.__probe"))
            time.sleep(0.2)
        print(f"| click-to-update latency (median of 10), {where} | {statistics.median(latencies):.0f} ms |")
        print(f"(server rendered {server_fps} frames in all)")
        browser.close()
    app.stop()


def pattern_window(app: App, page, where: str) -> None:
    """Five seconds of play: the page's update and frame rates, the server's, and the pixel ratio."""
    ratio = page.evaluate(PIXEL_RATIO)
    frames_before = app.frames
    page.evaluate(START_RECORD, [5000])
    frames, changes = page.evaluate("window.__probe")
    sent = (app.frames - frames_before) / 5.0
    print(
        f"| scene updates/s in the browser, {where} (pixel ratio {ratio:.2f}) | {len(changes) / 5.0:.1f} "
        f"| page frames/s {len(frames) / 5.0:.1f} | server frames/s {sent:.1f} |"
    )


def election_end(session: Session) -> int:
    """The event at which the leader first stands at its corner (Phase 3 begins), found by stepping a
    copy of the run without a browser: the run is deterministic, so the played one reaches it there."""
    while session.engine.outcome is None and not session.view().stage.startswith("Phase 3"):
        session.run.step()
    return session.engine.state.events


def election_window(frames: list[float], changes: list[list[float]], elected_at: int, where: str) -> None:
    """Print the update rate of the election (from the play's start to the first update showing the
    leader at its corner) and of the rest of the window."""
    ends = [t for t, event in changes if event >= elected_at]
    if not ends:
        print(f"(the election did not end within the window: {len(changes)} updates in 5 s)")
        end = 5000.0
    else:
        end = ends[0]
    times = [0.0] + [t for t, _ in changes if t <= end]  # the play's start, then each update in it
    during, after = len(times) - 1, len(changes) - (len(times) - 1)
    drawn = sum(1 for t in frames if t <= end)
    seconds = end / 1000
    gap = max(b - a for a, b in itertools.pairwise(times)) if during else end
    print(f"(leader election lasted {seconds:.2f} s of play: {elected_at} events, {during} updates shown)")
    print(f"| longest wait for an update during the election | {gap:.0f} ms |")
    print(f"| scene updates/s in the browser while playing, {where} | {during / seconds:.1f} |")
    print(f"| frames/s the page drew meanwhile (some show no new update) | {drawn / seconds:.1f} |")
    if ends and end < 4500:
        rest = (5000 - end) / 1000
        print(f"| scene updates/s after it, start of pattern formation ({rest:.1f} s) | {after / rest:.1f} |")


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


def reach_targets(session: Session) -> None:
    """Step the run without a browser until the line is complete and its first robot leaves it for its
    target (TargetMove, the paper's last stage; at 1,000 robots about four minutes, half a million moves;
    progress on stderr)."""
    engine = session.engine
    t0 = last = time.perf_counter()
    while engine.outcome is None:
        session.run.step()
        events = engine.history.steps[engine.step_index - 1].events
        if any("TargetMove" in (e.rule_id or "") for e in events):
            break
        if time.perf_counter() - last > 15:
            last = time.perf_counter()
            print(f"(stepping: {engine.state.moves:,} moves, {last - t0:.0f} s)", file=sys.stderr)
    took = time.perf_counter() - t0
    print(f"(stepped to the first TargetMove in {took:.0f} s, {engine.state.moves:,} moves)", file=sys.stderr)


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
        page.evaluate(START_RECORD, [2000])
        _, changes = page.evaluate("window.__probe")
        rate = len(changes) / 2.0
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
