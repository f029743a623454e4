"""`apf-viz` with no command serves the demo; `serve --trace` replays; a bad file is one line, exit 2."""

from __future__ import annotations

import subprocess
import sys
import time
import urllib.request

import pytest

import apf_viz.workbench.run_controller as run_controller
from apf_viz.ui.app import free_port


def serve(*args: str) -> tuple[subprocess.Popen, int]:
    port = free_port()
    proc = subprocess.Popen(
        [sys.executable, "-m", "apf_viz.cli", *args, "--port", str(port)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    return proc, port


def wait_for_page(port: int, proc: subprocess.Popen) -> str:
    end = time.time() + 90
    while time.time() < end:
        assert proc.poll() is None, proc.stderr.read()
        try:
            with urllib.request.urlopen(f"http://127.0.0.1:{port}/", timeout=1) as r:
                return r.read().decode()
        except OSError:
            time.sleep(0.2)
    raise AssertionError("the server did not answer")


@pytest.mark.parametrize("args", [(), ("serve", "--trace", "tests/gap_traces/E2.jsonl")])
def test_serves_and_prints_its_two_addresses(args):
    """One line each: the presenter's address (a secret in it) and the class's (none)."""
    proc, port = serve(*args)
    try:
        lines: dict[str, str] = {}
        for _ in range(50):  # the server prints its addresses once it is listening
            line = proc.stdout.readline()
            if not line:
                break
            key, _, value = line.strip().partition(": ")
            lines[key] = value
            if "class" in lines:
                break
        assert "presenter" in lines and "class" in lines, (lines, proc.stderr.read() if proc.poll() else "")
        # viser moves to the next port if the chosen one was taken meanwhile: use the printed address.
        follower = lines["class"]
        actual = int(follower.split("http://127.0.0.1:")[1].rstrip("/"))
        assert actual >= port and follower == f"http://127.0.0.1:{actual}/"
        presenter = lines["presenter"]
        secret = presenter.rsplit("/present/", 1)[1]
        assert presenter == f"{follower}?websocket=ws://127.0.0.1:{actual}/present/{secret}"
        assert len(secret) >= 20 and secret not in follower
        page = wait_for_page(actual, proc)
        assert "<html" in page.lower()
    finally:
        proc.terminate()
        proc.communicate(timeout=60)


def test_serve_with_a_bad_file_is_one_line_and_exit_2(tmp_path):
    bad = tmp_path / "r.json"
    bad.write_text('{"robots": [[0, 0], [0, 0]]}')
    proc, _ = serve("serve", "--robots", str(bad), "--pattern", "demo_patterns/pair-2.json")
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 2 and err.count("\n") == 1 and "duplicate robot at (0, 0)" in err


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (("--port", "99999"), "99999 is not a port"),
        (("--host", "256.1.1.1"), "cannot listen on 256.1.1.1"),
        (("--robots", "demo_patterns/starts/sym-call-7.json"), "pass --pattern"),
    ],
)
def test_bad_serve_options_are_one_line_errors(args, message):
    if "--port" not in args:  # not the default 8080: another server on this machine may hold it
        args = (*args, "--port", str(free_port()))
    proc = subprocess.run(
        [sys.executable, "-m", "apf_viz.cli", "serve", *args], capture_output=True, text=True, timeout=60
    )
    assert proc.returncode == 2 and message in proc.stderr and proc.stderr.count("\n") == 1, proc.stderr


def test_play_keeps_the_speed_asked_when_frames_run_a_little_short():
    """At a speed near FPS, frames a little shorter than 1/FPS still take a step each (a budget capped
    at exactly one frame's share lost the fraction: every other frame stepped nothing); a stalled
    frame is not made up in a burst."""
    from apf_viz.ui.app import FPS, play_budget

    budget, steps = 1.0, 0
    for _ in range(300):
        budget = play_budget(budget, 0.98 / FPS, float(FPS))
        while budget >= 1:
            budget, steps = budget - 1, steps + 1
    assert steps >= 0.98 * 300 - 1
    assert play_budget(0.0, 5.0, 2000.0) == 2000.0 / FPS + 1.0  # five seconds stalled: one frame's worth
    assert play_budget(0.0, 5.0, 2.0) == 2.0  # slow play: at most two steps at once


def test_a_call_of_play_takes_the_steps_that_fit_in_the_time_left_of_the_frame():
    """Dear steps (forced cycles in a crowd) shrink the next call at once; cheap ones let it grow back
    slowly; a call always takes a step, and never more than the budget."""
    from apf_viz.ui.app import StepPacer

    pacer = StepPacer()
    pacer.took(10, 0.010)  # a millisecond a step
    assert pacer.allowance(67, 0.020) == 20
    pacer.took(20, 0.0002)  # then cheap steps: the cost is forgotten a fifth at a time
    assert pacer.allowance(67, 0.020) == 25
    assert pacer.allowance(67, 0.0) == 1 and pacer.allowance(3.5, 1.0) == 3
    for _ in range(60):
        pacer.took(67, 0.00067)
    assert pacer.allowance(67, 0.020) == 67


def test_settling_memory_collects_garbage_and_exempts_what_survives():
    import gc
    import weakref

    from apf_viz.ui.app import settle_memory

    class Node:
        pass

    a, b = Node(), Node()
    a.other, b.other = b, a  # a cycle: only a collection frees it
    gone = weakref.ref(a)
    kept = [Node()]
    del a, b
    try:
        settle_memory()
        assert gone() is None and gc.get_freeze_count() > 0
        survivor = weakref.ref(kept[0])
        gc.collect()
        assert survivor() is kept[0]  # what survives is kept, frozen or not
    finally:
        gc.unfreeze()


def test_play_starts_without_a_full_collection_and_the_collection_comes_when_it_stops(monkeypatch):
    """A full collection at 1,000 robots is a frame's wait: the loop does it as it starts and when play
    stops, never between the Play click and the first step (only a freeze there)."""
    import apf_viz.ui.app as app_module
    from apf_viz.ui.app import App, demo_session

    calls: list[str] = []
    monkeypatch.setattr(app_module, "settle_memory", lambda: calls.append("settle"))
    monkeypatch.setattr(app_module, "freeze_for_play", lambda: calls.append("freeze"))
    app = App(demo_session(), port=free_port(), verbose=False)
    try:
        deadline = time.time() + 30
        while calls != ["settle"]:
            assert time.time() < deadline, calls
            time.sleep(0.05)
        events = app.session.engine.state.events
        app.session.toggle_play()
        while app.session.engine.state.events == events:
            assert time.time() < deadline, "play took no step"
            time.sleep(0.05)
        assert calls == ["settle", "freeze"]
        app.session.pause()
        while calls != ["settle", "freeze", "settle"]:
            assert time.time() < deadline, calls
            time.sleep(0.05)
    finally:
        app.stop()


@pytest.mark.parametrize("dear", [0, 10**9])
def test_a_step_leaving_many_robots_to_decide_is_drawn_before_the_next_step(monkeypatch, dear):
    """With ``DEAR_DECISIONS`` robots left to decide anew after a step, the loop draws a frame before the
    next step pays for them: at 0, every call of Play's stepping is followed by a frame; out of reach,
    a frame follows several (the demo at top speed)."""
    import apf_viz.ui.app as app_module
    from apf_viz.ui.app import App, demo_session

    monkeypatch.setattr(app_module, "DEAR_DECISIONS", dear)
    app = App(demo_session(), port=free_port(), verbose=False)
    calls, per_frame = [0], []
    play_steps, render = app.session.play_steps, app._render

    def counted_steps(allowance: int = 1) -> int:
        calls[0] += 1
        return play_steps(allowance)

    def counted_render() -> None:
        per_frame.append(calls[0])
        calls[0] = 0
        render()

    app.session.play_steps = counted_steps
    app._render = counted_render
    try:
        app.session.set_speed(run_controller.MAX_SPEED)
        app.session.toggle_play()
        deadline = time.time() + 30
        while len(per_frame) < 40 and app.session.playing:
            assert time.time() < deadline, per_frame
            time.sleep(0.05)
        app.session.pause()
    finally:
        app.stop()
    played = [n for n in per_frame if n]
    assert played
    assert (max(played) == 1) == (dear == 0), played


# ``python -m apf_viz.cli``, with a word on a pipe once the interpreter's own start is over. Before it,
# while Python imports its site module, a Ctrl+C is Python's "Fatal Python error: init_import_site",
# whatever the program (a few milliseconds on an idle machine, over 0.1 s on a loaded one); and for the
# millisecond after it, while runpy finds and reads apf_viz/__init__.py, no line of apf-viz has run yet
# either (docs/ARCHITECTURE.md, "Ctrl+C").
STARTED_THEN_CLI = (
    "import os, runpy, sys; os.write(int(sys.argv[1]), b'.'); sys.argv[:2] = ['-m']; "
    "runpy.run_module('apf_viz.cli', run_name='__main__', alter_sys=True)"
)


@pytest.mark.parametrize("after", [0.02, 0.05, 0.1, 0.3, 1.0, 2.5])
def test_ctrl_c_while_the_server_starts_stops_it_without_a_traceback(after):
    """At any moment once Python has started: while apf-viz imports, while viser starts, or once
    serving, the process ends and says no more than a line."""
    import os
    import signal

    read, write = os.pipe()
    proc = subprocess.Popen(
        [sys.executable, "-c", STARTED_THEN_CLI, str(write), "serve", "--port", str(free_port())],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        pass_fds=(write,),
    )
    os.close(write)
    assert os.read(read, 1) == b"."
    os.close(read)
    time.sleep(after)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    # Interrupted while it starts, it says so and returns 130; CPython then sometimes ends the process by
    # SIGINT itself (about one start in four here, with the same line said), which a shell reports as
    # 130 too.
    assert proc.returncode in (0, 130, -signal.SIGINT), err
    assert "Traceback" not in err and len(err.strip().splitlines()) <= 1, err


def test_serve_demo_opens_a_scenario_named_by_a_word():
    from apf_viz.cli import build_parser
    from apf_viz.cli.serve import session_config
    from apf_viz.demos import scenarios
    from apf_viz.workbench.config import session_from_config

    args = build_parser().parse_args(["serve", "--demo", "lockstep"])
    session = session_from_config(session_config(args))
    assert session.screen.scenario_note == scenarios()["The L2 lockstep counterexample"].shows
    assert session.run.following  # a trace scenario: Step follows it


def test_a_pages_malformed_messages_are_one_line_on_the_terminal_and_change_nothing():
    """Before, each was a traceback of 12–16 lines from websockets' handler (viser cannot decode it)."""
    import asyncio

    import msgspec
    import viser
    import websockets

    proc, port = serve("serve")
    try:
        wait_for_page(port, proc)
        bad = [
            msgspec.msgpack.encode({"type": "NoSuchMessage"}),
            msgspec.msgpack.encode({"type": "GuiUpdateMessage"}),
            msgspec.msgpack.encode([1, 2]),
            b"\xc1",
        ]

        async def send(payload: bytes) -> None:
            url, protocol = f"ws://127.0.0.1:{port}", f"viser-v{viser.__version__}"
            async with websockets.connect(url, subprotocols=[protocol]) as ws:
                try:
                    await ws.send(payload)
                    await asyncio.sleep(0.5)
                except websockets.exceptions.ConnectionClosed:
                    pass

        for payload in bad:
            asyncio.run(send(payload))
        wait_for_page(port, proc)  # still serving
    finally:
        proc.terminate()
        _, err = proc.communicate(timeout=30)
    lines = [line for line in err.splitlines() if line.strip()]
    assert "Traceback" not in err, err
    assert len(lines) == 1 and "a page sent a message the server could not use (KeyError" in lines[0], err


def test_one_line_holds_back_what_comes_within_its_interval():
    import logging

    from apf_viz.ui.page_errors import EVERY, OneLine

    now = [100.0]
    one = OneLine(clock=lambda: now[0])

    def record() -> logging.LogRecord:
        try:
            raise ValueError("bad\nmessage")
        except ValueError:
            return logging.LogRecord(
                "websockets.server", logging.ERROR, "x", 1, "failed", None, sys.exc_info()
            )

    first = record()
    assert one.filter(first) and first.exc_info is None and "\n" not in first.getMessage()
    assert not one.filter(record()) and not one.filter(record())
    now[0] += EVERY
    later = record()
    assert one.filter(later) and "2 more since" in later.getMessage()
    plain = logging.LogRecord("asyncio", logging.INFO, "x", 1, "no exception", None, None)
    assert one.filter(plain) and plain.getMessage() == "no exception"
    from websockets.exceptions import ConnectionClosedError

    try:  # a page that left without a goodbye (here: its move to its seat) is not a bad message
        raise ConnectionClosedError(None, None)
    except ConnectionClosedError:
        gone = logging.LogRecord("websockets.server", logging.ERROR, "x", 1, "failed", None, sys.exc_info())
    now[0] += EVERY
    assert not one.filter(gone)


def test_arrow_keys_on_the_speed_slider_climb_a_ladder_and_a_drag_lands_anywhere():
    """The slider's step is one of 5000: an arrow key (a change of exactly one) is read as the next rung
    of 1, 2, 5, 10, … 5000 that way, from any speed; any other change is the value sent."""
    from apf_viz.workbench.run_controller import MAX_SPEED, SPEED_LADDER, slider_speed

    up, down = [1.0], [MAX_SPEED]
    while up[-1] < MAX_SPEED:
        up.append(slider_speed(up[-1], up[-1] + 1))
    while down[-1] > 1:
        down.append(slider_speed(down[-1], down[-1] - 1))
    assert tuple(up) == SPEED_LADDER and tuple(down) == SPEED_LADDER[::-1]
    assert slider_speed(13, 14) == 20 and slider_speed(13, 12) == 10  # off the ladder: the next rung
    assert slider_speed(MAX_SPEED, MAX_SPEED + 1) == MAX_SPEED and slider_speed(1, 0) == 1
    assert slider_speed(10, 437) == 437 and slider_speed(10, 12) == 12  # dragged or typed
