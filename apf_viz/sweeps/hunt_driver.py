"""Driving a hunt on Dask (the sweep's local processes, or ``--cluster``): the biggest starts first, rows
written every few seconds and at the end, progress with an ETA, Ctrl+C (or SIGTERM) keeps what finished
and a later run resumes from it."""

from __future__ import annotations

import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from apf_viz.core.files import check_writable, make_folder
from apf_viz.explore.hunt import KEY, HuntStart, hunt_one
from apf_viz.progress import show_progress
from apf_viz.sweeps.driver import by_the_second, dask_client, duration, shut_down
from apf_viz.sweeps.hunt_table import read_hunt, write_hunt


@dataclass(frozen=True)
class HuntProgress:
    finished: int
    total: int
    failures: int
    budget: int
    seconds: float
    eta: float | None


def weight(start: HuntStart) -> float:
    """A start's expected cost, for the ETA and the order: the states grow with k and each costs a view
    of k robots for each of k robots (measured: k = 10 about 1 s, 20 about 5 s, 28 about 15 s)."""
    return 1.0 + (start.k / 10) ** 2.5


def run_hunt(
    starts: Sequence[HuntStart],
    out: Path,
    *,
    algorithm: str,
    max_states: int,
    counterexamples: Path | None = None,
    flips: str = "drawn",
    workers: int | None = None,
    cluster: str | None = None,
    progress: Callable[[HuntProgress], None] | None = None,
) -> list[dict]:
    """Search every start not already in ``out`` (a row whose search ran out of a smaller budget is
    searched again); returns every row of the table."""
    check_writable(out)
    kept = read_hunt(out)
    rows = [r for r in kept if r["verdict"] != "budget" or r["max_states"] >= max_states]
    if counterexamples is not None:
        make_folder(counterexamples)
    done = {tuple(r[c] for c in KEY) for r in rows}
    todo = [s for s in starts if (s.family, s.k, s.seed, algorithm, flips) not in done]
    todo.sort(key=weight, reverse=True)  # the biggest first: no long start left alone at the end
    if not todo:
        return rows
    client, local = dask_client(cluster, workers)
    folder = str(counterexamples) if counterexamples is not None else None
    futures = {client.submit(hunt_one, s, algorithm, max_states, folder, flips, pure=False): s for s in todo}
    total_weight = sum(weight(s) for s in todo)
    done_weight, failures, budget, t0, last_write = 0.0, 0, 0, time.monotonic(), time.monotonic()
    finished = 0
    try:
        for got, _pending in by_the_second(futures):
            for fut in got:
                start = futures[fut]
                r = _row(fut, start, algorithm, max_states, flips)
                rows = [x for x in rows if tuple(x[c] for c in KEY) != tuple(r[c] for c in KEY)] + [r]
                finished += 1
                done_weight += weight(start)
                failures += r["verdict"] not in ("verified", "budget")
                budget += r["verdict"] == "budget"
            if progress is not None:
                seconds = time.monotonic() - t0
                eta = seconds * (total_weight - done_weight) / done_weight if done_weight else None
                progress(HuntProgress(finished, len(todo), failures, budget, seconds, eta))
            if time.monotonic() - last_write > 5:
                write_hunt(out, rows)
                last_write = time.monotonic()
    except KeyboardInterrupt:
        write_hunt(out, rows)
        print("\napf-viz hunt: interrupted; keeping the starts that finished", file=sys.stderr)
        shut_down(futures, client, local)
        raise
    write_hunt(out, rows)
    shut_down(futures, client, local)
    return rows


def _row(fut, start: HuntStart, algorithm: str, max_states: int, flips: str) -> dict:
    try:
        return fut.result()
    except Exception as e:  # the search raised, or its worker died: the row says so
        return {
            "family": start.family, "k": start.k, "seed": start.seed, "algorithm": algorithm, "flips": flips,
            "D": 0,
            "verdict": "error", "states": 0, "max_states": max_states, "seconds": 0.0,
            "detail": f"{type(e).__name__}: {e}"[:500], "counterexample": "", "robots": "", "pattern": "",
            "y_up": "",
        }  # fmt: skip


def report_hunt(p: HuntProgress) -> None:
    eta = "ETA …" if p.eta is None else f"ETA {duration(p.eta)}"
    show_progress(
        f"apf-viz hunt: {p.finished}/{p.total} starts, {p.failures} failing, {p.budget} out of budget, "
        f"{duration(p.seconds)}, {eta}",
        last=p.finished >= p.total,
    )
