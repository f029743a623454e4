"""Driving a sweep on Dask: the runs as tasks, the biggest first; rows written as they finish; progress
with an ETA; a stuck or dead worker recorded as the run's error; Ctrl+C keeps what finished."""

from __future__ import annotations

import math
import sys
import time
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass, replace
from pathlib import Path

from apf_viz.core.files import check_writable, make_folder, remove_if_empty
from apf_viz.core.formats import InputError
from apf_viz.progress import show_progress
from apf_viz.sweeps.cells import KEY, WORST_FOUND, Cell, row, run_cell
from apf_viz.sweeps.results import read_results, write_results


@dataclass(frozen=True)
class Progress:
    """What a sweep reports while it runs (every finished run, and every second a run is still going)."""

    finished: int
    total: int
    failed: int
    seconds: float
    eta: float | None  # seconds, from the sizes of the runs left (None until one has finished)
    slowest: str = ""  # the run that has been running longest, and for how long


def cost(cell: Cell) -> float:
    """A run's expected time, in arbitrary units (about 80 µs each here): moves grow as k·D and each
    costs a little more in a bigger crowd (measured, docs/PERFORMANCE.md: k = 40 → 0.6 s, 100 → 1.8 s,
    300 → 21 s, 1,000 → 8 min), plus a fixed part per run (a task's round trip, tens of milliseconds).
    A walk across open ground is one step (fast-forward: 10 robots 10⁶ apart form in 0.1 s), so only
    the crowd's part of D counts: at most k."""
    from apf_viz.core.budget import paper_D

    # A generated start is not drawn just to be weighed: its box's side, or k, is its D.
    d = paper_D(cell.robots, cell.pattern) if cell.robots else max(cell.k, math.isqrt(3 * cell.k) + 1)
    one = 500.0 + (cell.k * min(d, max(cell.k, 3))) ** 1.2
    # WORST_FOUND: the built-ins' 100 runs, its budget's schedules, and about 20 runs' worth of beam.
    return one * (cell.search_budget + 120) if cell.scheduler == WORST_FOUND else one


def _describe(cell: Cell) -> str:
    where = cell.start or f"k={cell.k}"
    return f"{where} seed {cell.seed} {cell.scheduler} {cell.algorithm}"


def dask_client(cluster: str | None, workers: int | None):
    """A client of the given scheduler, or of a local cluster (no dashboard, no fixed port)."""
    import logging

    from dask.distributed import Client, LocalCluster

    if cluster:
        return _remote_client(Client, cluster), None
    local = LocalCluster(
        n_workers=workers or usable_cores(),
        threads_per_worker=1,
        processes=True,
        dashboard_address=None,
        # The scheduler serves HTTP (health, metrics) even without a dashboard, by default on 8787: a
        # second sweep, or anything else there, would get a warning. Any free port on loopback will do.
        scheduler_kwargs={"dashboard_address": "127.0.0.1:0"},
        # A worker's own log goes to our terminal: at shutdown a heartbeat to the scheduler that just
        # closed logs an ERROR with a traceback, reporting nothing lost. What a run raises, or a worker
        # that dies, reaches the results as that run's error instead.
        silence_logs=logging.CRITICAL,
    )
    return Client(local), local


CONNECT_SECONDS = 15.0
"""How long a Dask scheduler may take to answer: Dask's own timeout does not cover a peer that accepts
the connection and never speaks."""


def _remote_client(client_class, cluster: str):
    """A client of the scheduler at ``cluster``, made in a thread of its own so that a peer that never
    answers cannot hold the command: past :data:`CONNECT_SECONDS`, one line (the thread is left behind,
    a daemon, and ends with the process)."""
    import queue
    import threading

    made: queue.Queue = queue.Queue()

    def connect() -> None:
        try:
            made.put(client_class(cluster, timeout="10s"))
        except Exception as e:  # unreachable, or a protocol whose package is missing (ucx://)
            made.put(e)

    threading.Thread(target=connect, name="dask-connect", daemon=True).start()
    try:
        got = made.get(timeout=CONNECT_SECONDS)
    except queue.Empty:
        raise InputError(
            f"--cluster {cluster}: no Dask scheduler answered there within {CONNECT_SECONDS:.0f} s"
        ) from None
    if isinstance(got, Exception):
        reason = str(got) if str(got) not in ("", "None") else type(got).__name__
        raise InputError(f"--cluster {cluster}: cannot reach a Dask scheduler there ({reason})")
    return got


def run_sweep(
    cells: Sequence[Cell],
    out: Path,
    *,
    traces: Path | None = None,
    workers: int | None = None,
    cluster: str | None = None,
    run: Callable[[Cell, str | None], dict] = run_cell,
    progress: Callable[[Progress], None] | None = None,
    run_timeout: float | None = None,
) -> list[dict]:
    """Run every cell not already in ``out`` on Dask; rows are written as they come (every few
    seconds) and at the end, also after Ctrl+C. Returns all rows of the file."""
    check_writable(out)
    rows = read_results(out)  # before any work: a file that is not a results table is refused
    made = make_folder(traces) if traces is not None else []
    done = {tuple(r[c] for c in KEY) for r in rows}
    todo = [replace(c, timeout=run_timeout) for c in cells if c.key() not in done]
    if not todo:
        return rows
    try:
        client, local = dask_client(cluster, workers)
    except BaseException:
        remove_if_empty(made)
        raise
    futures = {client.submit(run, c, str(traces) if traces else None, pure=False): c for c in todo}
    tracker = _Tracker(client, futures, progress)
    try:
        for r in tracker.results():
            rows.append(r)
            if tracker.due_for_write():
                write_results(out, rows)
    except KeyboardInterrupt:
        write_results(out, rows)  # first: every run that finished is kept, whatever shutting down does
        print("\napf-viz sweep: interrupted; keeping the runs that finished", file=sys.stderr)
        shut_down(futures, client, local)
        raise
    write_results(out, rows)
    shut_down(futures, client, local)
    return rows


class _Tracker:
    """Waits for the sweep's runs and reports progress: finished, failed, an ETA weighted by the runs'
    sizes (:func:`cost`), and the run that has been running longest."""

    def __init__(self, client, futures: dict, progress: Callable[[Progress], None] | None) -> None:
        self.client, self.futures, self.progress = client, futures, progress
        self.total = len(futures)
        self.workers = max(1, len(client.scheduler_info().get("workers", {})))
        self.cost_left = sum(cost(c) for c in futures.values())
        self.cost_done = 0.0
        self.finished = self.failed = 0
        self.t0 = self.last_write = time.monotonic()
        self.started: dict[str, float] = {}  # task key → when it was first seen running

    def results(self):
        for finished, pending in by_the_second(self.futures):
            for fut in finished:
                r = self._row(fut)
                self.finished += 1
                self.failed += r["outcome"] != "formed"
                self.cost_done += cost(self.futures[fut])
                self.cost_left -= cost(self.futures[fut])
                self.started.pop(fut.key, None)
                yield r
            self._report(pending)

    def _row(self, fut) -> dict:
        cell = self.futures[fut]
        try:
            return fut.result()
        except Exception as e:  # the run raised, or its worker died (KilledWorker)
            return row(cell, 0, "error", 0, 0, 0, 0, 0.0, "", f"{type(e).__name__}: {e}"[:500])

    def due_for_write(self) -> bool:
        if time.monotonic() - self.last_write > 5:
            self.last_write = time.monotonic()
            return True
        return False

    def _report(self, pending: set) -> None:
        if self.progress is None:
            return
        now = time.monotonic()
        seconds = now - self.t0
        # The first runs also pay for the workers' imports: no estimate until a round of runs is done.
        warm = self.finished >= min(self.total, 2 * self.workers)
        eta = max(0.0, seconds * self.cost_left / self.cost_done) if warm and self.cost_done else None
        self.progress(
            Progress(self.finished, self.total, self.failed, seconds, eta, self._slowest(pending, now))
        )

    def _slowest(self, pending: set, now: float) -> str:
        if not pending:
            return ""
        try:  # a worker's queue counts as "processing" for the scheduler: ask what each one executes
            running = {key for keys in self.client.run(_executing).values() for key in keys}
        except Exception:  # a worker is busy or gone: no line is better than a wrong one
            return ""
        for key in running:
            self.started.setdefault(key, now)
        by_key = {f.key: f for f in pending}
        candidates = [(t, k) for k, t in self.started.items() if k in running and k in by_key]
        if not candidates:
            return ""
        t, key = min(candidates)
        return f"{_describe(self.futures[by_key[key]])} running {now - t:.0f} s"


def by_the_second(futures) -> Iterator[tuple[set, set]]:
    """(finished, still pending) futures, once a second or as soon as one finishes, until none is
    pending: a progress line keeps ticking while a long task runs."""
    from dask.distributed import wait

    pending = set(futures)
    while pending:
        try:
            finished, pending = wait(pending, timeout=1.0, return_when="FIRST_COMPLETED")
        except TimeoutError:
            finished = set()
        yield finished, pending


def _executing(dask_worker) -> list:
    """On a worker: the keys of the tasks it is running now (not those queued on it)."""
    return [ts.key for ts in dask_worker.state.executing]


def shut_down(futures, client, local) -> None:
    """Cancel what is queued and close the cluster quietly: once the results are written, Dask's own
    shutdown messages (a worker killed after 4 s, a heartbeat to a closed scheduler) report nothing
    lost. Dask may itself be interrupted mid-way (a second Ctrl+C): nothing is lost then either."""
    import logging

    loggers = [logging.getLogger(name) for name in ("distributed", "tornado", "asyncio")]
    levels = [lg.level for lg in loggers]
    for lg in loggers:
        lg.setLevel(logging.CRITICAL + 1)
    try:
        client.cancel([f for f in futures if not f.done()])
        client.close()
        if local is not None:
            local.close()
    except BaseException:
        pass
    finally:
        for lg, level in zip(loggers, levels, strict=True):
            lg.setLevel(level)


def usable_cores() -> int:
    import os

    return max(1, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1)


def report_progress(p: Progress) -> None:
    eta = "ETA …" if p.eta is None else f"ETA {duration(p.eta)}"
    slowest = f"; slowest: {p.slowest}" if p.slowest else ""
    line = f"apf-viz sweep: {p.finished}/{p.total} runs, {p.failed} not formed, {duration(p.seconds)}, {eta}"
    show_progress(f"{line}{slowest}", last=p.finished >= p.total)


def duration(seconds: float) -> str:
    if seconds < 120:
        return f"{seconds:.0f} s"
    if seconds < 7200:
        return f"{seconds / 60:.0f} min"
    return f"{seconds / 3600:.1f} h"


def summary(rows: Iterable[dict]) -> str:
    """Per algorithm × scheduler: runs, formed, failures by outcome, moves/(k·D) median and max."""
    import statistics

    groups: dict[tuple[str, str, str], list[dict]] = {}
    for r in rows:
        groups.setdefault((r["algorithm"], r["scheduler"], r["light_semantics"]), []).append(r)
    lines = ["| algorithm | scheduler | semantics | runs | formed | failures | moves/(k·D) median | max |",
             "|---|---|---|---:|---:|---|---:|---:|"]  # fmt: skip
    for (alg, sched, sem), rs in sorted(groups.items()):
        formed = [r for r in rs if r["outcome"] == "formed"]
        fails: dict[str, int] = {}
        for r in rs:
            if r["outcome"] != "formed":
                fails[r["outcome"]] = fails.get(r["outcome"], 0) + 1
        ratio = [r["moves_per_kD"] for r in formed]
        med = f"{statistics.median(ratio):.3f}" if ratio else "—"
        mx = f"{max(ratio):.3f}" if ratio else "—"
        failures = ", ".join(f"{k} {v}" for k, v in sorted(fails.items())) or "none"
        lines.append(f"| {alg} | {sched} | {sem} | {len(rs)} | {len(formed)} | {failures} | {med} | {mx} |")
    return "\n".join(lines)
