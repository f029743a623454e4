"""`apf-viz sweep`: thousands of runs on Dask, one results table.

The grid of runs is the product of the lists (k × seed × scheduler × algorithm × light semantics), or of
the start/pattern pairs of a folder instead of (k, seed). Each run is a task on a Dask cluster: by
default a ``LocalCluster`` of one single-threaded worker process per core; ``--cluster ADDRESS`` submits
to an existing scheduler. Results are one row per run (Parquet, or CSV by the file's extension), written
atomically as runs finish; re-running the same command skips the runs already in the file; Ctrl+C keeps
what finished. A run whose worker dies is recorded as ``error`` with the message, and the sweep goes on.

Reproducible starts (docs/SWEEPS.md): for (k, seed), the box is s × s with s = max(3, ⌊√(3k)⌋ + 1); the
robots are ``random_robots(k, s, s, 2·seed)`` (redrawn until solvable, as ``apf-viz random-robots``), the
pattern ``random_pattern(k, s, s, 2·seed + 1)``, the flips ``random_y_up(k, seed)``.
"""

from __future__ import annotations

import math
import sys
import time
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass, replace
from pathlib import Path

from apf_viz.algorithms.merged_lights import AtWork, MergedLights
from apf_viz.core.formats import InputError, check_writable, replace_atomically, write_atomic
from apf_viz.core.grid import as_point
from apf_viz.progress import show_progress

COLUMNS = (
    "k", "D", "seed", "scheduler", "algorithm", "light_semantics", "start", "outcome", "moves", "events",
    "cycles", "lights_used", "moves_per_kD", "wall_s", "trace", "error", "hidden",
)  # fmt: skip
# Added later: a table written before it still resumes (read as 0).
_LATER_COLUMNS = {"hidden": 0}
KEY = ("k", "seed", "scheduler", "algorithm", "light_semantics", "start")


@dataclass(frozen=True)
class Cell:
    """One run of the grid. ``start``: "" for a generated (k, seed) start, else the pair's name."""

    k: int
    seed: int
    scheduler: str
    algorithm: str
    light_semantics: str
    start: str = ""
    robots: tuple[tuple[int, int], ...] = ()
    pattern: tuple[tuple[int, int], ...] = ()
    y_up: tuple[bool, ...] = ()
    timeout: float | None = None  # seconds; a run past it is recorded as "timeout" (not part of the key)

    def key(self) -> tuple:
        return (self.k, self.seed, self.scheduler, self.algorithm, self.light_semantics, self.start)


MAX_VALUES = 100_000  # values one --ks or --seeds list may name
MAX_RUNS = 1_000_000  # runs one sweep may hold (its rows are kept in memory)
MAX_K = 100_000  # robots per generated start (random_configs.MAX_RANDOM_POINTS)


def parse_range(text: str, what: str) -> list[int]:
    """ "1-50" or "5,10,20" (or both: "1-3,7") as integers; a reversed range is refused, and so is a
    list of more than :data:`MAX_VALUES` values, counted before any is made."""
    parts: list[tuple[int, int]] = []
    for part in text.split(","):
        part = part.strip()
        lo, dash, hi = part[1:].partition("-")  # a leading minus is a sign, not a range
        try:
            a, b = (int(part[0] + lo), int(hi)) if dash else (int(part), int(part))
        except (ValueError, IndexError):
            raise InputError(f"{what} {text!r}: not a list of integers or ranges like 1-50") from None
        if b < a:
            raise InputError(f"{what} {text!r}: the range {part} runs backwards")
        parts.append((a, b))
    count = sum(b - a + 1 for a, b in parts)
    if count > MAX_VALUES:
        raise InputError(f"{what} {text!r}: {count:,} values, more than the {MAX_VALUES:,} a sweep takes")
    return [v for a, b in parts for v in range(a, b + 1)]


def generated_start(k: int, seed: int) -> tuple[list, list, list[bool]]:
    from apf_viz.core.frames import random_y_up
    from apf_viz.core.random_configs import random_pattern, random_robots

    side = max(3, math.isqrt(3 * k) + 1)
    return (
        random_robots(k, side, side, 2 * seed),
        random_pattern(k, side, side, 2 * seed + 1),
        list(random_y_up(k, seed)),
    )


def grid(
    ks: Sequence[int],
    seeds: Sequence[int],
    schedulers: Sequence[str],
    algorithms: Sequence[str],
    semantics: Sequence[str],
    starts: Path | None = None,
) -> list[Cell]:
    """The runs of the sweep; every name is checked first (one line for the first bad one)."""
    from apf_viz.algorithms import get_algorithm
    from apf_viz.core.schedulers import AUTOMATIC

    for name in algorithms:
        try:
            get_algorithm(name)
        except ValueError as e:
            raise InputError(f"--algorithms: {e}") from None
    choices = AUTOMATIC
    for s in schedulers:
        if s not in choices:
            raise InputError(f"--schedulers: unknown scheduler {s!r} (choose from {', '.join(choices)})")
    for s in semantics:
        if s not in ("compute", "lc-atomic"):
            raise InputError(
                f"--light-semantics: {s!r} is not compute or lc-atomic (choose from compute, lc-atomic)"
            )
    if starts is None and any(k < 1 for k in ks):
        raise InputError(f"--ks: a run needs at least one robot (got {min(ks)})")
    if starts is None and any(k > MAX_K for k in ks):
        raise InputError(f"--ks: at most {MAX_K:,} robots per run (got {max(ks):,})")
    if any(seed < 0 for seed in seeds):
        raise InputError(f"--seeds: seeds are 0 or more (got {min(seeds)})")
    pairs: list[tuple[str, int, list, list, list[bool]]] = []
    if starts is not None:
        pairs = [(name, 0, r, p, f) for name, r, p, f in start_pairs(starts)]
    runs = len(pairs or ks) * len(seeds) * len(schedulers) * len(algorithms) * len(semantics)
    if runs > MAX_RUNS:
        raise InputError(f"the sweep has {runs:,} runs, more than the {MAX_RUNS:,} one sweep takes; split it")
    cells = []
    for sched in schedulers:
        for alg in algorithms:
            for sem in semantics:
                if starts is not None:
                    for name, _, r, p, f in pairs:
                        shape = (tuple(r), tuple(p), tuple(f))
                        cells += [Cell(len(r), seed, sched, alg, sem, name, *shape) for seed in seeds]
                else:
                    for k in ks:
                        for seed in seeds:
                            cells.append(Cell(k, seed, sched, alg, sem))
    return cells


def start_pairs(folder: Path) -> list[tuple[str, list, list, list[bool]]]:
    """``NAME.robots.json`` with ``NAME.pattern.json`` in ``folder`` (docs/SWEEPS.md)."""
    from apf_viz.core.formats import check_sizes, load_pattern, load_robots

    if not folder.is_dir():
        raise InputError(f"--starts {folder}: not a folder")
    pairs = []
    for robots_file in sorted(folder.glob("*.robots.json")):
        name = robots_file.name.removesuffix(".robots.json")
        pattern_file = folder / f"{name}.pattern.json"
        if not pattern_file.is_file():
            raise InputError(f"{robots_file}: no {pattern_file.name} beside it")
        robots, pattern = load_robots(robots_file), load_pattern(pattern_file)
        check_sizes(robots, pattern, str(pattern_file))
        points = [as_point(p) for p in robots.robots]
        pairs.append((name, points, [as_point(p) for p in pattern.points], robots.flips(1)))
    if not pairs:
        raise InputError(f"--starts {folder}: no NAME.robots.json / NAME.pattern.json pairs")
    return pairs


def run_cell(cell: Cell, traces: str | None = None) -> dict:
    """One run, on a worker: its row (a trace is written only for a run that did not form)."""
    from apf_viz.algorithms import get_algorithm
    from apf_viz.core.budget import paper_D, run_budget
    from apf_viz.core.engine import Engine
    from apf_viz.core.formats import trace_text, write_atomic
    from apf_viz.core.run import advance, trace_header
    from apf_viz.core.schedulers import make_scheduler

    if cell.robots:
        robots, pattern, y_up = list(cell.robots), list(cell.pattern), list(cell.y_up)
    else:
        robots, pattern, y_up = generated_start(cell.k, cell.seed)
    budget = run_budget(robots, pattern)
    t0 = time.perf_counter()
    algorithm = get_algorithm(cell.algorithm)
    if isinstance(algorithm, MergedLights):
        algorithm = AtWork(algorithm)  # counts the decisions its merge is at work in (the light lab)
    engine = Engine(
        robots,
        pattern,
        algorithm,
        y_up=y_up,
        light_semantics=cell.light_semantics,  # type: ignore[arg-type]
        max_events=budget.max_events,
        max_moves=budget.max_moves,
        fast_forward=True,
    )
    scheduler = make_scheduler(cell.scheduler)
    if cell.timeout is None:
        advance(engine, scheduler, cell.seed)
    else:
        deadline = t0 + cell.timeout
        while not engine.finished and time.perf_counter() < deadline:
            advance(engine, scheduler, cell.seed, steps=_TIMEOUT_CHUNK)
    wall = time.perf_counter() - t0
    st = engine.state
    d = paper_D(robots, pattern)
    trace = ""
    if st.outcome != "formed" and traces:
        where = cell.start or f"k{cell.k}"
        name = f"{where}-s{cell.seed}-{cell.scheduler}-{cell.algorithm}-{cell.light_semantics}"
        path = Path(traces) / (name.replace("/", "_").replace("@", "_at_").replace(",", "+") + ".jsonl")
        header = trace_header(engine, cell.scheduler, cell.seed)
        write_atomic(path, trace_text(header, engine.history.events()))
        trace = str(path)
    outcome = st.outcome or "timeout"
    hidden = algorithm.count if isinstance(algorithm, AtWork) else 0
    return row(
        cell, d, outcome, st.moves, st.events, st.cycles, len(st.lights_used), wall, trace, hidden=hidden
    )


_TIMEOUT_CHUNK = 2_000  # steps between looks at the clock: milliseconds at any k


def row(
    cell: Cell, d, outcome, moves, events, cycles, lights, wall, trace, error: str = "", hidden: int = 0
) -> dict:
    return {
        "k": cell.k, "D": d, "seed": cell.seed, "scheduler": cell.scheduler, "algorithm": cell.algorithm,
        "light_semantics": cell.light_semantics, "start": cell.start, "outcome": outcome, "moves": moves,
        "events": events, "cycles": cycles, "lights_used": lights,
        "moves_per_kD": (moves / (cell.k * d)) if d else 0.0, "wall_s": round(wall, 4), "trace": trace,
        "error": error, "hidden": hidden,
    }  # fmt: skip


# ---------------------------------------------------------------------------------------------- results
def read_results(path: Path) -> list[dict]:
    """The rows of a results table, or [] when there is none; a file that is not a table this sweep
    wrote (another CSV, a Parquet file with other columns, notes) is refused, never overwritten."""
    if not path.exists():
        return []
    try:
        if path.suffix == ".csv":
            import csv

            with path.open(newline="", encoding="utf-8") as f:
                reader = csv.DictReader(f)
                _check_columns(path, reader.fieldnames or [])
                return [_typed({**_LATER_COLUMNS, **r}) for r in reader]
        import pyarrow.parquet as pq

        table = pq.read_table(path)
        _check_columns(path, table.column_names)
        return [{**_LATER_COLUMNS, **r} for r in table.to_pylist()]
    except InputError:
        raise
    except Exception as e:  # a file that is not a results table: say so rather than overwrite it
        raise InputError(
            f"{path}: not a results table this sweep can resume ({type(e).__name__}: {e})"
        ) from None


def _check_columns(path: Path, columns: Sequence[str]) -> None:
    missing = [c for c in COLUMNS if c not in columns and c not in _LATER_COLUMNS]
    extra = [c for c in columns if c not in COLUMNS]
    if missing or extra:
        what = f"missing columns {', '.join(missing)}" if missing else ""
        what += ("; " if missing and extra else "") + (
            f"columns it does not write: {', '.join(extra)}" if extra else ""
        )
        raise InputError(f"{path}: not a results table of apf-viz sweep ({what}); choose another --out")


def _typed(r: dict) -> dict:
    ints = ("k", "D", "seed", "moves", "events", "cycles", "lights_used", "hidden")
    floats = ("moves_per_kD", "wall_s")
    return {c: (int(v) if c in ints else float(v) if c in floats else v) for c, v in r.items()}


def write_results(path: Path, rows: list[dict]) -> None:
    rows = sorted(rows, key=lambda r: tuple(str(r[c]) for c in KEY))
    if path.suffix == ".csv":
        import csv
        import io

        buf = io.StringIO()
        w = csv.DictWriter(buf, fieldnames=list(COLUMNS))
        w.writeheader()
        w.writerows(rows)
        write_atomic(path, buf.getvalue())
        return
    import pyarrow as pa
    import pyarrow.parquet as pq

    table = pa.Table.from_pylist(rows, schema=_schema()) if rows else _schema().empty_table()
    replace_atomically(path, lambda tmp: pq.write_table(table, tmp))


def _schema():
    import pyarrow as pa

    types = {"moves_per_kD": pa.float64(), "wall_s": pa.float64()}
    text = ("scheduler", "algorithm", "light_semantics", "start", "outcome", "trace", "error")
    return pa.schema([(c, types.get(c, pa.string() if c in text else pa.int64())) for c in COLUMNS])


# ---------------------------------------------------------------------------------------------- driving
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
    costs a little more in a bigger crowd (measured, README: k = 40 → 0.6 s, 100 → 1.8 s, 300 → 21 s,
    1,000 → 8 min), plus a fixed part per run (a task's round trip, tens of milliseconds). A walk across
    open ground is one step (fast-forward: 10 robots 10⁶ apart form in 0.1 s), so only the crowd's part
    of D counts: at most k."""
    from apf_viz.core.budget import paper_D

    # A generated start is not drawn just to be weighed: its box's side, or k, is its D.
    d = paper_D(cell.robots, cell.pattern) if cell.robots else max(cell.k, math.isqrt(3 * cell.k) + 1)
    return 500.0 + (cell.k * min(d, max(cell.k, 3))) ** 1.2


def _describe(cell: Cell) -> str:
    where = cell.start or f"k={cell.k}"
    return f"{where} seed {cell.seed} {cell.scheduler} {cell.algorithm}"


def _client(cluster: str | None, workers: int | None):
    """A client of the given scheduler, or of a local cluster (no dashboard, no fixed port)."""
    import logging

    from dask.distributed import Client, LocalCluster

    if cluster:
        try:
            return Client(cluster, timeout="10s"), None
        except (OSError, TimeoutError) as e:
            reason = str(e) if str(e) not in ("", "None") else type(e).__name__
            raise InputError(f"--cluster {cluster}: cannot reach a Dask scheduler there ({reason})") from None
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
    if traces is not None:
        traces.mkdir(parents=True, exist_ok=True)
    done = {tuple(r[c] for c in KEY) for r in rows}
    todo = [replace(c, timeout=run_timeout) for c in cells if c.key() not in done]
    if not todo:
        return rows
    client, local = _client(cluster, workers)
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
        _shut_down(futures, client, local)
        raise
    write_results(out, rows)
    _shut_down(futures, client, local)
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


def _shut_down(futures, client, local) -> None:
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
    eta = "ETA …" if p.eta is None else f"ETA {_duration(p.eta)}"
    slowest = f"; slowest: {p.slowest}" if p.slowest else ""
    line = f"apf-viz sweep: {p.finished}/{p.total} runs, {p.failed} not formed, {_duration(p.seconds)}, {eta}"
    show_progress(f"{line}{slowest}", last=p.finished >= p.total)


def _duration(seconds: float) -> str:
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
