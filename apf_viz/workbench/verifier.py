"""`Verify` in the browser: the exhaustive explorer (`apf-viz check`) on the current start and pattern,
in a background thread, with progress and Cancel.

One verification at a time, for everyone (the run is shared). The explorer reports progress every
20,000 expanded states; Cancel takes effect at the next report. A violation's counterexample is replayed
by the real engine into a trace's text, which the session then follows like any loaded trace.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Mapping
from dataclasses import dataclass

from apf_viz.algorithms import Factory, get_algorithm
from apf_viz.core.algorithm import Algorithm
from apf_viz.explore.check import counterexample_text, explore
from apf_viz.workbench.run_config import RunConfig

MAX_K = 5  # beyond this the state space is out of reach of a browser's patience (docs/VERIFICATION.md)
MAX_STATES = 2_000_000
# The explorer's adversaries: every ASYNC interleaving covers ASYNC, stale-first, round-robin and Manual.
EXPLORED = {"fsync": "fsync", "ssync": "ssync"}


@dataclass(frozen=True)
class Status:
    """What the panel shows: ``state`` is idle, running, verified, violation, budget, cancelled or error."""

    state: str = "idle"
    states: int = 0
    frontier: int = 0
    rate: float = 0.0
    text: str = ""  # the verdict in words
    trace: str | None = None  # a violation's counterexample, as a trace file's text


class _Cancelled(Exception):
    pass


class Verifier:
    """Runs one exploration at a time; ``on_change`` is called from its thread on progress and at the end."""

    def __init__(self, on_change: Callable[[Status], None]) -> None:
        self._on_change = on_change
        self._lock = threading.Lock()
        self._status = Status()
        self._cancel = threading.Event()
        self._thread: threading.Thread | None = None

    @property
    def status(self) -> Status:
        """Where the verification stands (read from any thread)."""
        with self._lock:
            return self._status

    def start(self, config: RunConfig, plugins: Mapping[str, Factory] | None = None) -> str | None:
        """Start verifying ``config``'s start and pattern; returns why not, if it cannot."""
        k = len(config.robots)
        if k > MAX_K:
            return (
                f"Verify explores every schedule, which is feasible up to k = {MAX_K} robots; this run has "
                f"{k}. Use apf-viz check on a smaller start."
            )
        with self._lock:
            if self._status.state == "running":
                return "a verification is already running (Cancel it first)"
            self._cancel.clear()
            self._status = Status("running")
        algorithm = get_algorithm(config.algorithm, plugins)
        self._thread = threading.Thread(target=self._run, args=(config, algorithm), daemon=True)
        self._thread.start()
        return None

    def cancel(self) -> None:
        """Ask the running verification to stop: it does at its next progress report."""
        self._cancel.set()

    def wait(self, timeout: float | None = None) -> None:
        """Wait for the verification's thread to end (at most ``timeout`` seconds; None: for ever)."""
        if self._thread is not None:
            self._thread.join(timeout)

    def _progress(self, states: int, frontier: int, seconds: float) -> None:
        if self._cancel.is_set():
            raise _Cancelled
        with self._lock:
            self._status = Status("running", states, frontier, states / max(seconds, 1e-9))
        self._on_change(self.status)

    def _run(self, config: RunConfig, algorithm: Algorithm) -> None:
        scheduler = EXPLORED.get(config.scheduler, "async")
        try:
            result = explore(
                algorithm,
                config.robots,
                config.pattern,
                config.y_up,
                scheduler=scheduler,
                max_states=MAX_STATES,
                light_semantics=config.light_semantics,
                progress=self._progress,
            )
        except _Cancelled:
            status = Status("cancelled", text="cancelled: nothing is proved")
        except Exception as e:  # a verification must never kill the server
            status = Status("error", text=f"the explorer failed: {e}")
        else:
            how = f"{result.states:,} states, every {scheduler.upper()} schedule"
            if result.verdict == "verified":
                status = Status("verified", result.states, 0, 0.0, f"verified: {how}, with these flips")
            elif result.verdict == "budget":
                status = Status(
                    "budget", result.states, 0, 0.0, f"stopped at {result.states:,} states: {result.detail}"
                )
            else:
                trace = counterexample_text(
                    algorithm, config.robots, config.pattern, config.y_up, scheduler, result,
                    config.light_semantics,
                )  # fmt: skip
                status = Status(
                    "violation", result.states, 0, 0.0,
                    f"{result.verdict}: {result.detail.removeprefix(result.verdict + ': ')} ({how}); "
                    "counterexample loaded: Step follows it",
                    trace,
                )  # fmt: skip
        with self._lock:
            self._status = status
        self._on_change(status)
